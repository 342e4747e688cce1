"""EngineState: everything carried between cycles (goal list, each goal's last skill path), as
an explicit frozen value so a cycle is a pure function of (program, state, percepts)."""

from __future__ import annotations

from dataclasses import dataclass, field

from .errors import GoalError, LangError, StateError
from .goals import GoalEntry, parse_goal
from .terms import is_const

STATE_VERSION = 1


@dataclass(frozen=True, slots=True)
class StoredStep:
    """One skill on a remembered path: the goal instance text, the skill, its full bindings."""

    goal: str
    skill: int  # Skill.number
    skill_name: str
    bindings: tuple  # ((var name, value), ...) sorted by name

    def to_dict(self) -> dict:
        return {"goal": self.goal, "skill": self.skill, "skill_name": self.skill_name,
                "bindings": [[k, v] for k, v in self.bindings]}

    @classmethod
    def from_dict(cls, d: dict) -> StoredStep:
        return cls(str(d["goal"]), int(d["skill"]), str(d["skill_name"]),
                   tuple((str(k), v) for k, v in d["bindings"]))


@dataclass(frozen=True, slots=True)
class EngineState:
    """Goal list plus, per goal id, the path it last executed (used to prefer/resume it)."""

    goals: tuple[GoalEntry, ...] = ()
    paths: tuple[tuple[str, tuple[StoredStep, ...]], ...] = ()
    next_seq: int = 0
    cycle: int = 0
    extra: tuple = field(default=())  # reserved: problem-solver goal stacks, SCS threads

    def path_of(self, goal_id: str) -> tuple[StoredStep, ...]:
        """The remembered path of ``goal_id`` (empty if none)."""
        for gid, steps in self.paths:
            if gid == goal_id:
                return steps
        return ()

    def entry(self, goal_id: str) -> GoalEntry:
        for e in self.goals:
            if e.id == goal_id:
                return e
        raise GoalError(f"no goal with id {goal_id!r} (ids: {', '.join(e.id for e in self.goals)})")

    def to_dict(self) -> dict:
        """Plain data (str/int/float/list/dict) for JSON or msgpack."""
        return {"version": STATE_VERSION, "cycle": self.cycle, "next_seq": self.next_seq,
                "goals": [{"id": e.id, "goal": e.text, "priority": e.priority, "seq": e.seq,
                           "origin": e.origin} for e in self.goals],
                "paths": {gid: [s.to_dict() for s in steps] for gid, steps in self.paths}}

    @classmethod
    def from_dict(cls, d: dict) -> EngineState:
        """Inverse of to_dict; raises StateError naming what is wrong."""
        try:
            if d.get("version") != STATE_VERSION:
                raise StateError(f"engine state version {d.get('version')!r}, expected "
                                 f"{STATE_VERSION}")
            goals = tuple(GoalEntry(str(g["id"]), parse_goal(g["goal"]), int(g["priority"]),
                                    int(g["seq"]), str(g.get("origin", "user")))
                          for g in d["goals"])
            paths = tuple((str(gid), tuple(StoredStep.from_dict(s) for s in steps))
                          for gid, steps in sorted(d.get("paths", {}).items()))
            for _, steps in paths:
                for s in steps:
                    if not all(is_const(v) for _, v in s.bindings):
                        raise StateError(f"state path step {s.goal}: bindings must be constants")
            return cls(goals, paths, int(d["next_seq"]), int(d.get("cycle", 0)))
        except StateError:
            raise
        except (KeyError, TypeError, ValueError, AttributeError, LangError) as exc:
            raise StateError(f"engine state: bad shape ({type(exc).__name__}: {exc})") from None
