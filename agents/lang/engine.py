"""The Engine: inference + executive for one program, as pure functions of explicit state."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

from .errors import GoalError
from .executive import Executive
from .explanation import Decision
from .goals import GoalEntry, parse_goal
from .inference import Inference, InferStats
from .intake import PerceptCache, frame_of
from .program import Program
from .state import EngineState
from .store import BeliefSet, PerceptIndex, store_of
from .terms import Percept
from .tracker import check_frame


@dataclass(frozen=True, slots=True)
class CycleResult:
    """What one cycle produced: beliefs, the decision (actions + explanation), the next state."""

    beliefs: BeliefSet
    decision: Decision
    state: EngineState


def as_percepts(percepts: Iterable) -> list[Percept]:
    """Percept objects from Percepts or neutral lists ``["self", "ME", "speed", 20.0]``."""
    return [p if isinstance(p, Percept) else Percept.from_list(p) for p in percepts]


class Engine:
    """Runs a Program cycle by cycle. Holds compiled program data and what inference carries
    from cycle to cycle (``Inference``: last cycle's percept relations, facts and derivation
    counts), which only saves work: every result is exactly what a fresh Engine would give
    (docs/language.md, Performance)."""

    def __init__(self, program: Program):
        self.program = program
        self.inference = Inference(program)
        self.executive = Executive(program)
        self._checked: dict = {}  # type -> last Cols seen by ``decide`` (cheaper checks)
        self._percepts = PerceptCache(self._checked)  # and the Percepts made from them

    # -- goals ---------------------------------------------------------------------------
    def initial_state(self) -> EngineState:
        """Program goals with priorities 1..n in file order, ids p1..pn."""
        goals = tuple(GoalEntry(f"p{i + 1}", g.literal, i + 1, i, "program")
                      for i, g in enumerate(self.program.goals))
        return EngineState(goals, (), len(goals), 0)

    def add_goal(self, state: EngineState, goal: str, priority: int | None = None,
                 goal_id: str | None = None) -> EngineState:
        """Add ``goal`` (text such as ``(package-delivered PACKET2)``); it ranks after every goal
        with priority <= ``priority`` (default: last). Raises GoalError."""
        lit = parse_goal(goal, self.program)
        if priority is None:
            priority = max((e.priority for e in state.goals), default=0) + 1
        if not isinstance(priority, int) or isinstance(priority, bool):
            raise GoalError(f"goal {goal}: priority must be an int, got {priority!r}")
        gid = goal_id or f"g{state.next_seq + 1}"
        if any(e.id == gid for e in state.goals):
            raise GoalError(f"goal id {gid!r} is already in use")
        entry = GoalEntry(gid, lit, priority, state.next_seq, "user")
        return replace(state, goals=state.goals + (entry,), next_seq=state.next_seq + 1)

    def remove_goal(self, state: EngineState, goal_id: str) -> EngineState:
        """Drop a goal and its remembered path. Raises GoalError for an unknown id."""
        state.entry(goal_id)
        return replace(state, goals=tuple(e for e in state.goals if e.id != goal_id),
                       paths=tuple(p for p in state.paths if p[0] != goal_id))

    def set_priority(self, state: EngineState, goal_id: str, priority: int) -> EngineState:
        """Move a goal: it ranks after every goal with priority <= ``priority``."""
        old = state.entry(goal_id)
        new = replace(old, priority=priority, seq=state.next_seq)
        return replace(state, goals=tuple(new if e.id == goal_id else e for e in state.goals),
                       next_seq=state.next_seq + 1)

    # -- cycle ---------------------------------------------------------------------------
    @property
    def last_infer_stats(self) -> InferStats:
        """What the last ``infer``/``cycle`` did: strata evaluated and reused, percept tuples
        changed, derivations computed, concepts changed (for tests and bench)."""
        return self.inference.last_stats

    def infer(self, percepts: Iterable) -> BeliefSet:
        """Every concept instance that holds for this cycle's percepts (neutral lists as they
        come from the bus, Percepts, or a PerceptIndex). Raises LangError naming a bad
        percept."""
        beliefs = self.inference.beliefs(percepts)
        self.inference.frame = None  # hold no percept list past the call (fewer GC passes)
        return beliefs

    def decide(self, state: EngineState, percepts: Iterable, beliefs: Iterable):
        """The executive step: (Decision, next EngineState)."""
        return self.executive.decide(state, self._index(percepts), store_of(beliefs))

    def cycle(self, state: EngineState, percepts: Iterable) -> CycleResult:
        """infer + decide on the same percepts."""
        beliefs = self.inference.beliefs(percepts)
        index, self.inference.frame = self.inference.frame.index, None
        decision, new_state = self.executive.decide(state, index, beliefs.store)
        return CycleResult(beliefs, decision, new_state)

    def _index(self, percepts: Iterable) -> PerceptIndex:
        """The executive's index of ``percepts``, every value checked."""
        if isinstance(percepts, PerceptIndex):
            return percepts
        frame = frame_of(percepts)
        if not frame.checked:
            check_frame(frame, self._checked)
            frame.cache = self._percepts  # Percepts of unchanged rows are last cycle's
        else:
            self._checked.clear()
        return frame.index

