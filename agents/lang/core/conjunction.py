"""Conjunctive goals: ``(and L1 L2 ...)``, written wherever a goal is written (a
program's (goals ...), a scenario's [[goals]], ``teleo goal post``, ``teleo step --goal``).

A conjunction is read as the body of a concept without head arguments (seed 000, Table 2's
``:relations``): its conjuncts are literals, ``(not ...)`` literals and tests such as
``(< ?n 3)``; its variables are existential, as a concept's are, so it holds when one binding
makes every conjunct hold. The executive pursues one conjunct at a time, in the order the
impasse handler's ``agenda`` gives (agents/lang/solving/ordering.py; the written order without
one), and the means-ends problem solver decomposes it by concept chaining; no skill is ever
learned with a conjunction as its head (docs/language.md, "Conjunctive goals").
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

from .matcher import solve
from .sexpr import Atom, SList, to_text
from .store import FactStore, PerceptIndex
from .terms import Literal, Loc, Test, Var

AND = "and"


@dataclass(frozen=True, slots=True)
class Conjunction:
    """``(and c1 c2 ...)``: ``conds`` are Literals (possibly negated) and Tests, as written.
    ``pred`` and ``args`` let code that lists goals by concept treat it as the pseudo-concept
    ``and`` with no arguments (no skill or concept is ever named so)."""

    conds: tuple[Literal | Test, ...]
    loc: Loc | None = field(default=None, compare=False)

    pred = AND
    args = ()
    negated = False

    def __str__(self) -> str:
        return "(and " + " ".join(str(c) for c in self.conds) + ")"

    def variables(self) -> set[Var]:
        out: set[Var] = set()
        for c in self.conds:
            out |= c.variables()
        return out

    @property
    def literals(self) -> tuple[Literal, ...]:
        """The conjuncts that are literals (tests left out)."""
        return tuple(c for c in self.conds if isinstance(c, Literal))


Goal = Literal | Conjunction
"""What a goal is: one concept literal, or a conjunction of conditions."""


class _Reader(Protocol):
    def err(self, node: Atom | SList, msg: str, severity: str = "error") -> None: ...
    def loc(self, node: Atom | SList) -> Loc: ...
    def conditions(self, node: SList | None, tests: bool = True) -> list: ...


def is_conjunction(node: object) -> bool:
    """True for a form ``(and ...)``."""
    return (isinstance(node, SList) and bool(node.items) and isinstance(node.items[0], Atom)
            and node.items[0].value == AND)


def read_conjunction(p: _Reader, node: SList) -> Conjunction | None:
    """The conjunction written at ``node`` (``(and ...)``), or None after reporting why not
    through ``p.err``: no conjunct, a nested ``(and ...)``, or a test whose variables no
    positive literal binds."""
    items = node.items[1:]
    if not items:
        p.err(node, "a conjunctive goal needs at least one conjunct, such as "
                    "(and (on A B) (on B C)); got (and)")
        return None
    for item in items:
        if is_conjunction(item):
            p.err(item, f"a conjunct cannot itself be a conjunction: write its conjuncts in "
                        f"the outer (and ...), got {to_text(item)}")
            return None
    conds = p.conditions(SList(tuple(items), node.line, node.col))
    if len(conds) != len(items):   # each one refused has been reported
        return None
    bound: set[Var] = set()
    for c in conds:
        if isinstance(c, Literal) and not c.negated:
            bound |= c.variables()
    for c, item in zip(conds, items, strict=True):
        free = sorted(v.name for v in c.variables() - bound) if isinstance(c, Test) else []
        if free:
            p.err(item, f"variable ?{free[0]} of test {c} in {to_text(node)} is bound by no "
                        "positive conjunct; bind it in a literal such as (on ?x B)")
            return None
    return Conjunction(tuple(conds), p.loc(node))


def conjunction_holds(conj: Conjunction, store: FactStore,
                      pidx: PerceptIndex | None = None) -> bool:
    """True when one binding of the conjunction's variables makes every conjunct hold."""
    return first_binding(conj, store, pidx) is not None


def first_binding(conj: Conjunction, store: FactStore,
                  pidx: PerceptIndex | None = None) -> dict | None:
    """The first binding (in the matcher's order) under which every conjunct holds, or None."""
    return next(solve(list(conj.conds), {}, pidx or PerceptIndex(), store), None)


def goal_literals(goal: Goal) -> tuple[Literal, ...]:
    """The concept literals a goal names: itself, or a conjunction's literal conjuncts."""
    return goal.literals if isinstance(goal, Conjunction) else (goal,)
