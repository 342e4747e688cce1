"""The Engine: inference + executive for one program, as pure functions of explicit state
(program, state, percepts, and the outcomes of the previous cycle's actions). Part of the
assembly (docs/architecture.md): it runs the program's mechanisms (the registered ones,
agents/lang/registry.py, for a program built by hand)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

from .core.errors import GoalError, LangError
from .core.explanation import Decision
from .core.mechanism import slot_kinds
from .core.outcomes import as_outcomes
from .core.program import Program
from .core.store import BeliefSet, FactStore, PerceptIndex, store_of
from .core.terms import Percept
from .execution.executive import Executive, ImpasseHandler
from .execution.state import EngineState
from .inference.inference import Inference, InferStats
from .inference.shared_rows import Framer, SharedPercepts, check_new_rows
from .inference.tracker import check_frame
from .reading.extend import extend_program
from .reading.goals import GoalEntry, enumerable, parse_goal
from .registry import MECHANISMS, handlers


@dataclass(frozen=True, slots=True)
class CycleResult:
    """What one cycle produced: beliefs, the decision (actions + explanation), the next state."""

    beliefs: BeliefSet
    decision: Decision
    state: EngineState


def as_percepts(percepts: Iterable) -> list[Percept]:
    """Percept objects from Percepts or neutral lists ``["self", "ME", "speed", 20.0]``."""
    return [p if isinstance(p, Percept) else Percept.from_list(p) for p in percepts]


SOLVERS: dict[str, type] = handlers(MECHANISMS)
"""Impasse handlers by name, from the registered mechanisms: seed 000's means-ends problem
solver and learner, seed 003's ROGUE planner (agents/lang/planning); each an ImpasseHandler
(agents/lang/execution/executive.py: its hooks)."""


class _Adopted(ImpasseHandler):
    """A handler written to the duck-typed protocol of earlier releases (any object with
    ``solve``): its own hooks, the base class's no-ops for those it lacks."""

    def __init__(self, handler: object) -> None:
        self.handler = handler
        for name in HOOKS:
            hook = getattr(handler, name, None)
            if callable(hook):
                setattr(self, name, hook)


HOOKS = tuple(n for n, v in vars(ImpasseHandler).items() if callable(v) and n[0] != "_")


def adopted(solver: object) -> ImpasseHandler | None:
    """``solver`` as an ImpasseHandler: itself, adopted when it only has the hooks (at least
    ``solve``), or None when it is no handler at all."""
    if isinstance(solver, ImpasseHandler):
        return solver
    return _Adopted(solver) if callable(getattr(solver, "solve", None)) else None


class Engine:
    """Runs a Program cycle by cycle. Holds compiled program data and what inference carries
    from cycle to cycle (``Inference``: last cycle's percept relations, facts and derivation
    counts), which only saves work: every result is exactly what a fresh Engine would give
    (docs/language.md, Performance).
    ``solver``: what answers an impasse, a name in SOLVERS (default: the means-ends problem
    solver), an ImpasseHandler, or None (an impasse stays an impasse)."""

    def __init__(self, program: Program, solver: ImpasseHandler | str | None = "means-ends"):
        self.program = program
        if not program.mechanisms:   # built by hand: run with the registered mechanisms
            program = self.program = replace(program, mechanisms=MECHANISMS)
        self.mechanisms = program.mechanisms
        solvers = handlers(self.mechanisms)
        if isinstance(solver, str) and solver not in solvers:
            raise LangError(f"Engine: unknown solver {solver!r}; known: {', '.join(solvers)}")
        self.solver = solvers[solver]() if isinstance(solver, str) else \
            ImpasseHandler() if solver is None else adopted(solver)
        if self.solver is None:
            raise LangError(f"Engine: solver must be a name ({', '.join(solvers)}), an "
                            f"ImpasseHandler or None, got {type(solver).__name__} (it has no "
                            f"solve method)")
        self.inference = Inference(program)
        self.executive = Executive(program, self.solver)
        # shared rows only (the executive process's input): last cycle's grouping and the
        # Percepts of its rows; plain lists are read afresh, which at the demo's load and at
        # 1000 objects costs no more than keeping their columns did (docs/benchmarks.md)
        self._framer = Framer()
        self._shared = SharedPercepts()
        self._extended: dict[tuple[str, ...], Executive] = {(): self.executive}
        readers = [r for r in (m.model_reader(program) for m in self.mechanisms) if r]
        self._read_model = readers[0] if readers else None  # what a world model may hold

    # -- goals ---------------------------------------------------------------------------
    def initial_state(self, seed: int = 0, learned: tuple[str, ...] = ()) -> EngineState:
        """Program goals with priorities 1..n in file order, ids p1..pn; ``seed`` for the
        agent's nondeterministic choices; ``learned``: skill clauses (text) to start from."""
        goals = tuple(GoalEntry(f"p{i + 1}", g.literal, i + 1, i, "program")
                      for i, g in enumerate(self.program.goals))
        state = EngineState(goals, (), len(goals), 0, seed=seed, learned=tuple(learned),
                            slots=tuple((k, t()) for k, t in slot_kinds(self.mechanisms)))
        self.executive_for(state)   # a bad learned clause is refused now, not mid-run
        return state

    def executive_for(self, state: EngineState) -> Executive:
        """The executive of the program extended by the state's learned skills (cached)."""
        ex = self._extended.get(state.learned)
        if ex is None:
            ex = Executive(extend_program(self.program, state.learned), self.solver)
            self._extended[state.learned] = ex
        return ex

    def add_goal(self, state: EngineState, goal: str, priority: int | None = None,
                 goal_id: str | None = None, once: bool = False,
                 deadline: int | None = None) -> EngineState:
        """Add ``goal`` (text such as ``(package-delivered PACKET2)``); it ranks after every goal
        with priority <= ``priority`` (default: last). ``once``: dropped when achieved, not
        kept; ``deadline`` [cycles]: failed unless achieved within that many cycles from
        this state's cycle. Raises GoalError."""
        lit = parse_goal(goal, self.program)
        why = enumerable(lit, self.program)
        if why:
            raise GoalError(f"goal {lit}: {why}")
        if priority is None:
            priority = max((e.priority for e in state.goals), default=0) + 1
        if not isinstance(priority, int) or isinstance(priority, bool):
            raise GoalError(f"goal {goal}: priority must be an int, got {priority!r}")
        gid = goal_id or f"g{state.next_seq + 1}"
        if any(e.id == gid for e in state.goals):
            raise GoalError(f"goal id {gid!r} is already in use")
        if deadline is not None and (type(deadline) is not int or deadline < 1):
            raise GoalError(f"goal {goal}: deadline must be a whole number of cycles >= 1, "
                            f"got {deadline!r}")
        entry = GoalEntry(gid, lit, priority, state.next_seq, "user", bool(once),
                          -1 if deadline is None else state.cycle + deadline)
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

    def infer(self, percepts: Iterable, model: Iterable = ()) -> BeliefSet:
        """Every concept instance that holds for this cycle's percepts (neutral lists as they
        come from the bus, Percepts, or a PerceptIndex; LangError names a bad one) and the
        agent's world model (``model``: facts as neutral lists or tuples, asserted by SCS
        bodies; in the processes they come back with the world state, docs/bus.md "Agent
        memory"; a fact of a predicate the program neither defines nor asserts, or of the
        wrong arity, is a StateError)."""
        if model and self._read_model is None:
            raise LangError("Engine.infer: no mechanism of this engine keeps a world model")
        facts = self._read_model(model) if model else ()
        beliefs = self.inference.beliefs(percepts, facts)
        self.inference.frame = None  # nothing of this reading is kept for decide
        return beliefs

    def decide(self, state: EngineState, percepts: Iterable, beliefs: Iterable,
               outcomes: Iterable = ()) -> tuple[Decision, EngineState]:
        """The executive step: (Decision, next EngineState). ``outcomes``: the world's report
        on the previous cycle's actions (Outcome values or neutral dicts). It reads ``percepts``
        itself, whatever ``infer`` was given before: no state passes from ``infer`` to
        ``decide``, so a list changed in place between the two is read as it is now, as a fresh
        Engine would read it."""
        return self._decide(state, self._index(percepts), store_of(beliefs), outcomes)

    def cycle(self, state: EngineState, percepts: Iterable,
              outcomes: Iterable = ()) -> CycleResult:
        """infer + decide on the same percepts; the state's world model (facts asserted by
        SCS bodies in earlier cycles) joins inference as base facts. Within this one call
        the executive takes inference's reading of the percepts (nothing can change them in
        between)."""
        beliefs = self.inference.beliefs(percepts, self.facts(state))
        index, self.inference.frame = self.inference.frame.index, None
        decision, new_state = self._decide(state, index, beliefs.store, outcomes)
        return CycleResult(beliefs, decision, new_state)

    def facts(self, state: EngineState) -> tuple:
        """The base facts the mechanisms add to inference (the SCS world model: facts
        asserted by bodies in earlier cycles)."""
        return tuple(fact for m in self.mechanisms for fact in m.facts(state))

    def _index(self, percepts: Iterable) -> PerceptIndex:
        """The executive's index of ``percepts``, every value checked."""
        if isinstance(percepts, PerceptIndex):
            return percepts
        frame = self._framer.frame_of(percepts)
        try:
            if frame.patched is not None:  # shared rows: only the new ones need a check
                check_new_rows(frame)
            elif not frame.checked:  # (Percept objects need none)
                check_frame(frame)
        except LangError:
            self._framer = Framer()  # a refused message is no base for the next one
            raise
        if frame.shared:
            frame.cache = self._shared.bind(frame)
        return frame.index

    def _decide(self, state: EngineState, index: PerceptIndex, store: FactStore,
                outcomes: Iterable) -> tuple[Decision, EngineState]:
        store = self.solver.known(state, store)
        decision, new_state = self.executive_for(state).decide(state, index, store,
                                                               as_outcomes(outcomes))
        return self.solver.finish(decision, new_state)
