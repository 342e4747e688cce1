"""EngineState: everything carried between cycles, as an explicit frozen value so a cycle is a
pure function of (program, state, percepts, outcomes): the goal list, each goal's last skill
path, which goals acted last cycle, failed goals, the agent's seed, learned skills, and one
slot per mechanism (agents/lang/core/mechanism.py: its ``slot`` key and ``state_type``), each with
its own to_dict/from_dict, so a restarted executive loses none of them. The kernel names no
mechanism: the slots kept by default are those the registry (agents/lang/registry.py) hands
to ``use_slots``; a slot reads as an attribute (``state.scs``) and is replaced as a field
(``replace(state, scs=...)``)."""

from __future__ import annotations

import hashlib
import random
from dataclasses import dataclass
from typing import Any

from ..core.errors import GoalError, LangError, StateError
from ..core.terms import is_const
from ..reading.goals import GoalEntry, parse_goal
from .loops import LoopState

STATE_VERSION = 2

NO_LOOPS = LoopState()

SLOTS: dict[str, type] = {}
"""Slot key -> state type of the registered mechanisms, in registry order (the order of their
keys in the state file); filled by ``use_slots``."""


def use_slots(kinds: tuple[tuple[str, type], ...]) -> None:
    """Make ``kinds`` ((slot key, state type), ...) the slots every EngineState keeps by
    default (called once by agents/lang/registry.py)."""
    SLOTS.clear()
    SLOTS.update(kinds)


@dataclass(frozen=True, slots=True)
class StoredStep:
    """One skill on a remembered path: the goal instance text, the skill, its full bindings."""

    goal: str
    skill: int  # Skill.number
    skill_name: str
    bindings: tuple  # ((var name, value), ...) sorted by name

    def __repr__(self) -> str:
        # the dataclass's own text, written out: the loop watch hashes the remembered paths'
        # text every cycle (loops.intention), and the generated repr's recursion guard tripled
        # its cost (tests/lang/test_small_case.py holds the two texts equal)
        return f"StoredStep(goal={self.goal!r}, skill={self.skill!r}, " \
               f"skill_name={self.skill_name!r}, bindings={self.bindings!r})"

    def to_dict(self) -> dict:
        return {"goal": self.goal, "skill": self.skill, "skill_name": self.skill_name,
                "bindings": [[k, v] for k, v in self.bindings]}

    @classmethod
    def from_dict(cls, d: dict) -> StoredStep:
        return cls(str(d["goal"]), int(d["skill"]), str(d["skill_name"]),
                   tuple((str(k), v) for k, v in d["bindings"]))


@dataclass(frozen=True, slots=True, init=False)
class EngineState:
    """Goal list plus, per goal id, the path it last executed (used to prefer/resume it).

    ``active``: ids of the goals whose path acted last cycle (a goal not among them resumes
    its remembered path only if every skill on it could be started now); ``failed``: goals
    given up on, with the reason; ``seed``: the agent's seed for nondeterministic choices;
    ``learned``: skill clauses learned at run time, in program syntax (seed 000); ``loops``:
    the loop watch of every unsatisfied goal (agents/lang/execution/loops.py); ``slots``:
    (key, state) of each mechanism, every registered key present (its empty state by
    default), in registry order, then any other."""

    goals: tuple[GoalEntry, ...] = ()
    paths: tuple[tuple[str, tuple[StoredStep, ...]], ...] = ()
    next_seq: int = 0
    cycle: int = 0
    seed: int = 0
    active: tuple[str, ...] = ()
    failed: tuple[tuple[str, str], ...] = ()
    learned: tuple[str, ...] = ()
    loops: LoopState = LoopState()
    slots: tuple[tuple[str, Any], ...] = ()

    def __init__(self, goals: tuple[GoalEntry, ...] = (),
                 paths: tuple[tuple[str, tuple[StoredStep, ...]], ...] = (),
                 next_seq: int = 0, cycle: int = 0, seed: int = 0,
                 active: tuple[str, ...] = (), failed: tuple[tuple[str, str], ...] = (),
                 learned: tuple[str, ...] = (), loops: LoopState = NO_LOOPS,
                 slots: tuple[tuple[str, Any], ...] = (), **named: Any):
        """The fields, and the mechanism slots by key (``scs=...``) or as ``slots``."""
        table = {k: None for k in SLOTS}
        table.update(slots)
        table.update(named)
        for k, v in table.items():
            if v is None:
                table[k] = SLOTS[k]()
        for name, value in (("goals", goals), ("paths", paths), ("next_seq", next_seq),
                            ("cycle", cycle), ("seed", seed), ("active", active),
                            ("failed", failed), ("learned", learned), ("loops", loops),
                            ("slots", tuple(table.items()))):
            object.__setattr__(self, name, value)

    def __getattr__(self, name: str) -> Any:
        """A mechanism's slot by its key (``state.scs``)."""
        if not name.startswith("_"):
            for k, v in object.__getattribute__(self, "slots"):
                if k == name:
                    return v
        raise AttributeError(f"EngineState has no field or mechanism slot {name!r}")

    def rng(self, tag: str) -> random.Random:
        """A random generator for this cycle and purpose, derived from the agent's seed (the
        same seed, cycle and tag give the same draws in any process: lockstep stays
        deterministic through a restart)."""
        key = f"{self.seed}/{self.cycle}/{tag}".encode()
        return random.Random(int.from_bytes(hashlib.sha256(key).digest()[:8], "big"))

    def failure_of(self, goal_id: str) -> str | None:
        """Why goal ``goal_id`` failed, or None if it has not."""
        return dict(self.failed).get(goal_id)

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
                "seed": self.seed,
                "goals": [_goal_dict(e) for e in self.goals],
                "paths": {gid: [s.to_dict() for s in steps] for gid, steps in self.paths},
                "active": list(self.active), "failed": {g: why for g, why in self.failed},
                "learned": list(self.learned),
                **{k: v.to_dict() for k, v in self.slots},
                "loops": self.loops.to_dict()}

    @classmethod
    def from_dict(cls, d: dict, kinds: tuple[tuple[str, type], ...] | None = None
                  ) -> EngineState:
        """Inverse of to_dict; raises StateError naming what is wrong. ``kinds``: the
        mechanism slots to read ((key, state type), ...; default: the registered ones)."""
        kinds = tuple(SLOTS.items()) if kinds is None else kinds
        try:
            if d.get("version") != STATE_VERSION:
                raise StateError(f"engine state version {d.get('version')!r}, expected "
                                 f"{STATE_VERSION}")
            goals = tuple(GoalEntry(str(g["id"]), parse_goal(g["goal"]), int(g["priority"]),
                                    int(g["seq"]), str(g.get("origin", "user")),
                                    bool(g.get("once", False)), int(g.get("deadline", -1)),
                                    str(g.get("ended", "")))
                          for g in d["goals"])
            paths = tuple((str(gid), tuple(StoredStep.from_dict(s) for s in steps))
                          for gid, steps in sorted(d.get("paths", {}).items()))
            for _, steps in paths:
                for s in steps:
                    if not all(is_const(v) for _, v in s.bindings):
                        raise StateError(f"state path step {s.goal}: bindings must be constants")
            return cls(goals, paths, int(d["next_seq"]), int(d.get("cycle", 0)),
                       int(d.get("seed", 0)), tuple(str(g) for g in d.get("active", ())),
                       tuple((str(g), str(w)) for g, w in sorted(d.get("failed", {}).items())),
                       tuple(str(t) for t in d.get("learned", ())),
                       slots=tuple((k, t.from_dict(d.get(k, {}))) for k, t in kinds),
                       loops=LoopState.from_dict(d.get("loops", {})))
        except StateError:
            raise
        except (KeyError, TypeError, ValueError, AttributeError, LangError) as exc:
            raise StateError(f"engine state: bad shape ({type(exc).__name__}: {exc})") from None


def _goal_dict(e: GoalEntry) -> dict:
    """A goal entry as plain data; once, deadline and ended only when set (so the state of a
    run without them is what it was)."""
    d = {"id": e.id, "goal": e.text, "priority": e.priority, "seq": e.seq, "origin": e.origin}
    if e.once:
        d["once"] = True
    if e.deadline >= 0:
        d["deadline"] = e.deadline
    if e.ended:
        d["ended"] = e.ended
    return d
