"""The step tree of an SCS skill body, read from ``:body`` (seed 002, Appendix C).

A step is an atomic action ``(*name arg ...)``, an atomic group ``(atomic STEP ...)``, a
subgoal ``(LITERAL)``, a world-model update ``(assert (FACT))`` / ``(retract (FACT))``, a
wait point ``(wait COND ...)`` (seed 002, section 3, "Multiple Threads of Execution"), or a
construct ``(NAME MODS STEP ...)``: ``do``, ``do-all``, ``do-any``, ``repeat`` and their
starred forms take steps; ``do-first`` takes ``(CONDS STEP)`` pairs and ``do-best``
``(CONDS :utility EXPR [:reward EXPR] STEP)`` alternatives. MODS are ``:while``,
``:until``, ``:when``, ``:unless``, each followed by CONDS: one condition or a list of them
(agents/lang/scs/reader.py).

Every node is a frozen value that knows where it was written; a running step is addressed by
the child indices leading to it from the body's root (``node_at``).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from ..core.terms import ActionTemplate, Expr, Literal, Loc, Var, fmt


class Kind(StrEnum):
    """The construct families of Appendix C (the star is a separate flag)."""

    DO = "do"
    ALL = "do-all"
    ANY = "do-any"
    FIRST = "do-first"
    BEST = "do-best"
    REPEAT = "repeat"


CONSTRUCTS: dict[str, tuple[Kind, bool]] = {
    "do": (Kind.DO, False), "do*": (Kind.DO, True),
    "do-all": (Kind.ALL, False), "do*-all": (Kind.ALL, True),
    "do-any": (Kind.ANY, False), "do*-any": (Kind.ANY, True),
    "do-first": (Kind.FIRST, False), "do*-first": (Kind.FIRST, True),
    "do-best": (Kind.BEST, False), "do*-best": (Kind.BEST, True),
    "repeat": (Kind.REPEAT, False), "repeat*": (Kind.REPEAT, True),
}
MODIFIERS = (":while", ":until", ":when", ":unless")
SPECIAL = ("atomic", "assert", "retract", "wait")
WORDS = (*CONSTRUCTS, *SPECIAL)


@dataclass(frozen=True, slots=True)
class Mods:
    """A construct's modifiers; None where not given (``()`` is an empty, true, condition)."""

    while_: tuple | None = None
    until: tuple | None = None
    when: tuple | None = None
    unless: tuple | None = None

    def items(self) -> list[tuple[str, tuple]]:
        """(keyword, conditions) of the modifiers given, in the order :when :unless :while
        :until (the order they are checked in)."""
        pairs = ((":when", self.when), (":unless", self.unless), (":while", self.while_),
                 (":until", self.until))
        return [(k, v) for k, v in pairs if v is not None]


@dataclass(frozen=True, slots=True)
class Act:
    """An atomic action ``(*name arg ...)``: succeeds or fails as the world reports."""

    action: ActionTemplate
    loc: Loc | None = None

    def __str__(self) -> str:
        return str(self.action)


@dataclass(frozen=True, slots=True)
class ModelUpdate:
    """``(assert (FACT))`` or ``(retract (FACT))``: changes the agent's world model."""

    fact: Literal
    retract: bool = False
    loc: Loc | None = None

    def __str__(self) -> str:
        return f"({'retract' if self.retract else 'assert'} {self.fact})"


@dataclass(frozen=True, slots=True)
class Atomic:
    """``(atomic STEP ...)``: actions (and model updates) done together in one cycle, in
    order, with no condition checked between them; fails if any action fails."""

    steps: tuple  # Act | ModelUpdate
    loc: Loc | None = None

    def __str__(self) -> str:
        return "(atomic " + " ".join(str(s) for s in self.steps) + ")"


@dataclass(frozen=True, slots=True)
class Subgoal:
    """``(LITERAL)``: achieve a concept through the skill hierarchy."""

    literal: Literal
    loc: Loc | None = None

    def __str__(self) -> str:
        return str(self.literal)


@dataclass(frozen=True, slots=True)
class Wait:
    """``(wait COND ...)``: the thread stops here until the conditions hold."""

    conds: tuple
    loc: Loc | None = None

    def __str__(self) -> str:
        return "(wait " + " ".join(str(c) for c in self.conds) + ")"


@dataclass(frozen=True, slots=True)
class Branch:
    """One ``(CONDS STEP)`` of do-first, or ``(CONDS :utility EXPR [:reward EXPR] STEP)`` of
    do-best. ``utility``/``reward`` are expressions (None when not given)."""

    conds: tuple
    step: Any
    utility: object = None
    reward: object = None
    loc: Loc | None = None

    def __str__(self) -> str:
        conds = "(" + " ".join(str(c) for c in self.conds) + ")"
        util = f" :utility {fmt(self.utility)}" if self.utility is not None else ""
        return f"({conds}{util} {self.step})"


@dataclass(frozen=True, slots=True)
class Construct:
    """``(NAME MODS STEP ...)``; for do-first and do-best the steps are Branch values."""

    kind: Kind
    star: bool
    mods: Mods
    steps: tuple
    loc: Loc | None = None

    @property
    def name(self) -> str:
        """As written: ``do*-best``, ``repeat*``, ``do``."""
        if not self.star:
            return self.kind.value
        return "repeat*" if self.kind is Kind.REPEAT else "do*" + self.kind.value[2:]

    def __str__(self) -> str:
        first = children(self)[0]
        more = " ..." if len(self.steps) > 1 else ""
        text = f"({self.name} {first}{more})"
        return text if len(text) <= 60 else f"({self.name} ...)"


Step = Act | Atomic | Subgoal | ModelUpdate | Wait | Construct


def children(node: object) -> tuple:
    """The child steps of a node (a Branch's step for do-first/do-best)."""
    if isinstance(node, Construct):
        return tuple(s.step if isinstance(s, Branch) else s for s in node.steps)
    return ()


_USES: dict[int, tuple[object, frozenset]] = {}


def uses(node: object) -> frozenset:
    """The variables a step (with everything inside it) reads: in actions, subgoals, facts,
    conditions, utilities and rewards (cached per node)."""
    hit = _USES.get(id(node))
    if hit is not None and hit[0] is node:
        return hit[1]
    found: set = set()
    for _, n in walk_steps(node):
        if isinstance(n, Act):
            found |= n.action.variables()
        elif isinstance(n, Subgoal):
            found |= n.literal.variables()
        elif isinstance(n, ModelUpdate):
            found |= n.fact.variables()
        elif isinstance(n, Atomic):
            found |= set().union(*(uses(x) for x in n.steps))
        elif isinstance(n, Wait):
            found |= set().union(*(c.variables() for c in n.conds))
        elif isinstance(n, Construct):
            for _, conds in n.mods.items():
                found |= set().union(*(c.variables() for c in conds))
            for br in n.steps:
                if isinstance(br, Branch):
                    found |= set().union(*(c.variables() for c in br.conds))
                    for e in (br.utility, br.reward):
                        found |= expr_vars(e)
    result = frozenset(found)
    _USES[id(node)] = (node, result)
    return result


def expr_vars(e: object) -> set:
    if isinstance(e, Var):
        return {e}
    return e.variables() if isinstance(e, Expr) else set()


def node_at(root: object, at: tuple[int, ...]) -> object:
    """The step at address ``at`` below ``root``."""
    node = root
    for i in at:
        node = children(node)[i]
    return node


def walk_steps(root: object, at: tuple[int, ...] = ()):
    """Every (address, step) of a body, parents before children."""
    yield at, root
    for i, c in enumerate(children(root)):
        yield from walk_steps(c, (*at, i))
