"""The problem solver's part of EngineState: one goal stack per goal in impasse, with the
decision taken at each level (seed 000, "Problem Solving and Skill Learning": "pushes the
selected subgoal onto a goal stack and records details about its decisions for future use"),
kept between cycles and across a restart of the executive process (to_dict/from_dict).

Literals are kept as program text (``(unstackable B A)``), so the state is plain data; read
back with ``condition``, ``goal_of`` and ``literal``, and written with ``grounded``."""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Any

from ..core.conjunction import Conjunction
from ..core.errors import GoalError, LangError
from ..core.sexpr import Atom, read
from ..core.terms import Literal, Test
from ..execution.paths import show
from ..reading.goals import parse_goal
from ..reading.parser import Parser, Parts

SKILL = "skill"       # skill chaining: achieve the start of a skill whose head is the goal
CONCEPT = "concept"   # concept chaining: achieve the subconcepts of the goal's definition
CONJUNCTION = "conjunction"   # concept chaining on a conjunctive goal's conjuncts


@dataclass(frozen=True, slots=True)
class Alternative:
    """One way to chain off a goal: a skill clause (``kind`` SKILL, ``clause`` its
    Skill.number) or a concept clause (``kind`` CONCEPT, ``clause`` its 1-based index), with
    bindings; ``conditions`` are what must hold (the skill's :start and :requires, or the
    concept's :relations), ground, in written order; ``shows`` names it for people:
    ``(unstack B A)`` for a primitive skill, ``clear#2 (clear A)`` otherwise."""

    kind: str
    clause: int
    name: str
    bindings: tuple[tuple[str, Any], ...]
    conditions: tuple[str, ...]
    shows: str

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "clause": self.clause, "name": self.name,
                "bindings": [[k, v] for k, v in self.bindings],
                "conditions": list(self.conditions), "shows": self.shows}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Alternative:
        return cls(str(d["kind"]), int(d["clause"]), str(d["name"]),
                   tuple((str(k), v) for k, v in d["bindings"]),
                   tuple(str(c) for c in d["conditions"]), str(d["shows"]))


@dataclass(frozen=True, slots=True)
class StackEntry:
    """One level of a goal stack: the (sub)goal, the alternatives found for it (computed at
    its first decision), the one chosen (-1: none, either not yet or because the last one
    failed; ``tried``: how many were given up, so the next to try) and what was seen since
    it was chosen:
    ``initial`` the conditions that held when it was chosen, ``lost`` those of them that became
    false since, ``order`` the conditions (re)achieved since, in the order achieved,
    ``starts`` the start condition of whatever achieved each of them (for learning).
    ``pushes``: the conditions pushed for the chosen way so far, in order;
    ``executed``: cycles an executable path for this entry ran without achieving it;
    ``done``: the skill (number, bindings) last executed for it; ``failures``: why the
    alternatives tried before the chosen one failed."""

    goal: str
    why: str = ""
    alternatives: tuple[Alternative, ...] = ()
    chosen: int = -1
    initial: tuple[str, ...] = ()
    lost: tuple[str, ...] = ()
    order: tuple[str, ...] = ()
    starts: tuple[tuple[str, tuple[str, ...]], ...] = ()
    executed: int = 0
    done: tuple[int, tuple[tuple[str, Any], ...]] | None = None
    failures: tuple[str, ...] = ()
    tried: int = 0
    pushes: tuple[str, ...] = ()

    @property
    def decision(self) -> Alternative | None:
        """The alternative chosen at this level, if any."""
        return self.alternatives[self.chosen] if self.chosen >= 0 else None

    def choose(self, index: int, initial: tuple[str, ...]) -> StackEntry:
        """This entry with alternative ``index`` chosen afresh."""
        return replace(self, chosen=index, tried=index, initial=initial, lost=(), order=(),
                       starts=(), executed=0, done=None, pushes=())

    def give_up(self, why: str) -> StackEntry:
        """This entry with its chosen alternative given up (``why``): the next decision tries
        the next one."""
        way = self.decision
        if way is None:
            return self
        return replace(self, failures=self.failures + (f"{way.shows}: {why}",), chosen=-1,
                       tried=self.chosen + 1)

    def to_dict(self) -> dict[str, Any]:
        return {"goal": self.goal, "why": self.why,
                "alternatives": [a.to_dict() for a in self.alternatives],
                "chosen": self.chosen, "initial": list(self.initial), "lost": list(self.lost),
                "order": list(self.order),
                "starts": [[c, list(s)] for c, s in self.starts], "executed": self.executed,
                "done": None if self.done is None else
                [self.done[0], [[k, v] for k, v in self.done[1]]],
                "failures": list(self.failures), "tried": self.tried,
                "pushes": list(self.pushes)}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> StackEntry:
        done = d.get("done")
        return cls(str(d["goal"]), str(d.get("why", "")),
                   tuple(Alternative.from_dict(a) for a in d.get("alternatives", ())),
                   int(d.get("chosen", -1)), _texts(d.get("initial")), _texts(d.get("lost")),
                   _texts(d.get("order")),
                   tuple((str(c), _texts(s)) for c, s in d.get("starts", ())),
                   int(d.get("executed", 0)),
                   None if done is None else
                   (int(done[0]), tuple((str(k), v) for k, v in done[1])),
                   _texts(d.get("failures")), int(d.get("tried", 0)), _texts(d.get("pushes")))


@dataclass(frozen=True, slots=True)
class GoalStack:
    """The goal stack of one goal of the goal list (``goal_id``), bottom (the goal instance in
    impasse) first; ``started``: the cycle problem solving on it began; ``conflicts``: the
    goals of higher priority that a way was left out for, since it would undo them ("g1 (on
    B1 B4)"), named when the goal fails."""

    goal_id: str
    entries: tuple[StackEntry, ...]
    started: int = 0
    conflicts: tuple[str, ...] = ()

    @property
    def top(self) -> StackEntry:
        return self.entries[-1]

    def goals(self) -> list[str]:
        """The (sub)goals on the stack, bottom first."""
        return [e.goal for e in self.entries]

    def to_dict(self) -> dict[str, Any]:
        return {"goal_id": self.goal_id, "started": self.started,
                "entries": [e.to_dict() for e in self.entries],
                **({"conflicts": list(self.conflicts)} if self.conflicts else {})}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> GoalStack:
        return cls(str(d["goal_id"]), tuple(StackEntry.from_dict(e) for e in d["entries"]),
                   int(d.get("started", 0)), _texts(d.get("conflicts")))


@dataclass(frozen=True, slots=True)
class SolverState:
    """Every goal stack, by goal id (sorted), carried from one cycle to the next."""

    stacks: tuple[GoalStack, ...] = ()

    def stack_of(self, goal_id: str) -> GoalStack | None:
        """The goal stack of ``goal_id``, if problem solving is under way on it."""
        return next((s for s in self.stacks if s.goal_id == goal_id), None)

    def to_dict(self) -> dict[str, Any]:
        return {"stacks": [s.to_dict() for s in self.stacks]} if self.stacks else {}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> SolverState:
        return cls(tuple(GoalStack.from_dict(s) for s in d.get("stacks", ())))


def _texts(items: Any) -> tuple[str, ...]:
    return tuple(str(x) for x in items or ())


@lru_cache(maxsize=4096)
def condition(text: str) -> Literal | Test:
    """A condition (literal, ``(not ...)`` or test) read back from its program text."""
    forms, _ = read(f"({text})", "<solver>")
    parts = Parts()
    found = Parser("<solver>", parts).conditions(forms[0] if forms else None)
    if len(found) != 1 or parts.diags:
        raise ValueError(f"solver state: cannot read the condition {text!r}")
    return found[0]


@lru_cache(maxsize=1024)
def goal_of(text: str) -> Literal | Conjunction:
    """A (sub)goal read back from its text: a literal, or the conjunction at the bottom of a
    conjunctive goal's stack."""
    if text.startswith("(and "):
        try:
            return parse_goal(text)
        except GoalError as exc:
            raise ValueError(f"solver state: cannot read the goal {text!r}: {exc}") from None
    return literal(text)


def literal(text: str) -> Literal:
    """A (sub)goal read back from its text."""
    cond = condition(text)
    if not isinstance(cond, Literal):
        raise ValueError(f"solver state: {text!r} is not a literal")
    return cond


def pushable(cond: Literal | Test) -> bool:
    """Only a positive, ground literal can become a subgoal (no skill achieves a negation or
    a test; a variable would leave the subgoal open)."""
    return isinstance(cond, Literal) and not cond.negated and not cond.variables()


def grounded(conds: list, b: dict) -> list | None:
    """``conds`` with ``b``'s values written in, read back (the solver keeps its goals and
    learns its skills as program text); None when a value does not read back as itself (a
    symbol that is empty, spaced, a number or a variable as text: only a malformed percept or
    belief holds one): such a binding is no way to chain off."""
    if not all(map(_writable, b.values())):
        return None
    try:
        return [condition(show(c, b)) for c in conds]
    except (ValueError, LangError):
        return None


@lru_cache(maxsize=4096)
def _writable(value: object) -> bool:
    """Whether ``value`` (a binding's constant) reads back from its text as itself."""
    if not isinstance(value, str):
        return True   # numbers print as they read
    forms, diags = read(value, "<solver>")
    return not diags and len(forms) == 1 and isinstance(forms[0], Atom) and \
        forms[0].value == value
