"""EngineState: everything carried between cycles, as an explicit frozen value so a cycle is a
pure function of (program, state, percepts, outcomes): the goal list, each goal's last skill
path, which goals acted last cycle, failed goals, the agent's seed, learned skills, and one
named field per mechanism (problem solver, SCS bodies, planner), each with its own
to_dict/from_dict, so a restarted executive loses none of them."""

from __future__ import annotations

import hashlib
import random
from dataclasses import dataclass

from .errors import GoalError, LangError, StateError
from .goals import GoalEntry, parse_goal
from .loops import LoopState
from .planning.state import PlannerState
from .scs.state import ScsState
from .solving.state import SolverState
from .terms import is_const

STATE_VERSION = 2


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
    """Goal list plus, per goal id, the path it last executed (used to prefer/resume it).

    ``active``: ids of the goals whose path acted last cycle (a goal not among them resumes
    its remembered path only if every skill on it could be started now); ``failed``: goals
    given up on, with the reason; ``seed``: the agent's seed for nondeterministic choices;
    ``learned``: skill clauses learned at run time, in program syntax (seed 000); ``loops``:
    the loop watch of every unsatisfied goal (agents/lang/loops.py)."""

    goals: tuple[GoalEntry, ...] = ()
    paths: tuple[tuple[str, tuple[StoredStep, ...]], ...] = ()
    next_seq: int = 0
    cycle: int = 0
    seed: int = 0
    active: tuple[str, ...] = ()
    failed: tuple[tuple[str, str], ...] = ()
    learned: tuple[str, ...] = ()
    solver: SolverState = SolverState()
    scs: ScsState = ScsState()
    planner: PlannerState = PlannerState()
    loops: LoopState = LoopState()

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
                "goals": [{"id": e.id, "goal": e.text, "priority": e.priority, "seq": e.seq,
                           "origin": e.origin} for e in self.goals],
                "paths": {gid: [s.to_dict() for s in steps] for gid, steps in self.paths},
                "active": list(self.active), "failed": {g: why for g, why in self.failed},
                "learned": list(self.learned), "solver": self.solver.to_dict(),
                "scs": self.scs.to_dict(), "planner": self.planner.to_dict(),
                "loops": self.loops.to_dict()}

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
            return cls(goals, paths, int(d["next_seq"]), int(d.get("cycle", 0)),
                       int(d.get("seed", 0)), tuple(str(g) for g in d.get("active", ())),
                       tuple((str(g), str(w)) for g, w in sorted(d.get("failed", {}).items())),
                       tuple(str(t) for t in d.get("learned", ())),
                       SolverState.from_dict(d.get("solver", {})),
                       ScsState.from_dict(d.get("scs", {})),
                       PlannerState.from_dict(d.get("planner", {})),
                       LoopState.from_dict(d.get("loops", {})))
        except StateError:
            raise
        except (KeyError, TypeError, ValueError, AttributeError, LangError) as exc:
            raise StateError(f"engine state: bad shape ({type(exc).__name__}: {exc})") from None
