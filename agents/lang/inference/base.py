"""Base facts: the agent's world model (facts asserted by SCS bodies, seed 002) joining
inference, kept in step cycle by cycle like the percepts.

A concept's base facts enter through a rule of their own, ``(p ?a ?b) <- base p (?a ?b)``,
reading the relation ``("#base", p)`` of the percept store, so that they count as derivations
next to the concept's clauses (a fact asserted and also inferred holds while either does). A
predicate that is no concept (only asserted) has its base facts as its facts."""

from __future__ import annotations

import marshal
from collections.abc import Iterable

from ..core.columns import EMPTY, Summary, summarize_values
from ..core.store import FactStore
from ..core.terms import Var
from .rules import Elem, Rule
from .tracker import diff_relation

BASE = "#base"  # first item of a base relation's key: ("#base", pred)


def base_rule(pred: str, arity: int) -> Rule:
    """``(pred ?v0 ...)`` holds for every base fact of ``pred``."""
    head = tuple(Var(f"v{i}") for i in range(arity))
    return Rule(pred, head, (Elem((BASE, pred), head, False, True),), (), frozenset(head),
                f"({pred}{''.join(' ' + str(v) for v in head)}) base")


class BaseFacts:
    """Last run's base facts, and their strict change into the next run's."""

    def __init__(self, concepts: Iterable[str]):
        self.concepts = frozenset(concepts)
        self.key = marshal.dumps((), 2)
        self.sets: dict[str, set] = {}
        self.summary: Summary = EMPTY

    def summary_of(self, base: tuple) -> Summary:
        """The values of ``base`` that could clash with others (``columns.Summary``)."""
        if marshal.dumps(tuple(base), 2) == self.key:
            return self.summary
        return summarize_values([v for row in base for v in row[1:]])

    def update(self, base: tuple, edb: FactStore, idb: FactStore, deltas: dict) -> None:
        """Put into ``deltas`` the change of every base relation (``edb``: a concept's, keyed
        ("#base", pred); ``idb``: an asserted-only predicate's)."""
        key = marshal.dumps(tuple(base), 2)
        if key == self.key:
            return
        sets: dict[str, set] = {}
        for row in base:
            sets.setdefault(row[0], set()).add(tuple(row[1:]))
        for pred in sorted(set(sets) | set(self.sets)):
            new = sets.get(pred, set())
            if pred in self.concepts:
                diff_relation((BASE, pred), new, edb, deltas)
            else:
                diff_relation(pred, new, idb, deltas)
        self.key, self.sets = key, sets
        self.summary = summarize_values([v for row in base for v in row[1:]])

    def plain(self) -> dict[str, set]:
        """The base facts of predicates that are no concept (their whole fact sets)."""
        return {p: ts for p, ts in self.sets.items() if p not in self.concepts}
