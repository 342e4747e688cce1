"""Concept clauses in the form inference evaluates: joins over relations.

Every percept pattern becomes a positive literal over a percept relation: ``(block ?b xpos ?x
ypos ?y)`` reads ``("block", ("xpos", "ypos"))``, whose tuples are ``(id, xpos, ypos)``
(attributes sorted by name, so patterns naming the same attributes share a relation). Concept
literals read concept relations (facts keyed by predicate). So a clause is a head, a list of
elements (positive or negated literals) and tests, and an element's change can be joined with
the rest the same way whatever it reads (seed 000, "Inference and Execution Mechanisms")."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from operator import itemgetter

from ..core.program import ConceptClause
from ..core.terms import PerceptPattern, Test, Var


@dataclass(frozen=True, slots=True)
class Elem:
    """One body element: a positive or negated literal over relation ``rel``."""

    rel: object  # concept predicate (str) or percept relation (type, attrs)
    args: tuple  # Var or constant per position
    negated: bool = False
    percept: bool = False

    def variables(self) -> set[Var]:
        return {a for a in self.args if isinstance(a, Var)}


def percept_elem(p: PerceptPattern) -> Elem:
    """The literal over a percept relation that ``p`` stands for."""
    attrs = sorted(p.attrs, key=itemgetter(0))
    return Elem((p.type, tuple(a for a, _ in attrs)), (p.id, *(t for _, t in attrs)),
                False, True)


@dataclass(frozen=True, slots=True)
class Negation:
    """How a negated element is keyed: ``keys`` are the positions holding constants or variables
    bound outside it; the rest are existential. ``matches(t)``: a tuple agrees with the
    literal's constants and repeated variables."""

    keys: tuple[int, ...]
    consts: tuple[tuple[int, object], ...]
    same: tuple[tuple[int, int], ...]

    def matches(self, t: tuple) -> bool:
        return all(t[p] == c for p, c in self.consts) and all(t[p] == t[q] for p, q in self.same)

    def key(self, t: tuple) -> tuple:
        return tuple(t[p] for p in self.keys)


@dataclass(frozen=True)
class Rule:
    """A compiled clause: head predicate and arguments, elements (percept patterns first, then
    concept literals, as written) and tests."""

    pred: str
    head: tuple
    elems: tuple[Elem, ...]
    tests: tuple[Test, ...]
    outer: frozenset  # variables bound by positive elements, the head or tests
    label: str

    @classmethod
    def of(cls, clause: ConceptClause) -> Rule:
        elems = tuple([percept_elem(p) for p in clause.percepts] +
                      [Elem(r.pred, tuple(r.args), r.negated) for r in clause.relations])
        outer = set(clause.head.variables())
        for e in elems:
            if not e.negated:
                outer |= e.variables()
        for t in clause.tests:
            outer |= t.variables()
        return cls(clause.head.pred, tuple(clause.head.args), elems, tuple(clause.tests),
                   frozenset(outer), f"{clause.head} #{clause.index}")

    def negation(self, j: int) -> Negation:
        """Keying of negated element ``j``."""
        return self._negations[j]

    @cached_property
    def _negations(self) -> dict[int, Negation]:
        return {j: self._negation(j) for j, e in enumerate(self.elems) if e.negated}

    def _negation(self, j: int) -> Negation:
        args = self.elems[j].args
        keys = tuple(p for p, a in enumerate(args) if not isinstance(a, Var) or a in self.outer)
        consts = tuple((p, a) for p, a in enumerate(args) if not isinstance(a, Var))
        first: dict[Var, int] = {}
        same = []
        for p, a in enumerate(args):
            if isinstance(a, Var):
                if a in first:
                    same.append((p, first[a]))
                else:
                    first[a] = p
        return Negation(keys, consts, tuple(same))

    def reads(self) -> set:
        return {e.rel for e in self.elems}
