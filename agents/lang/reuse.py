"""Reuse of inference work across cycles, per stratum, without changing any result.

A stratum (an SCC of concepts) is a function of two inputs only: the percepts of the types its
clauses match and the facts of the lower concepts its clauses read. So when both are exactly
last cycle's, evaluating it again would give exactly last cycle's facts, and those are taken
instead. Percepts are compared in a canonical, order-independent form
(``PerceptIndex.signature``: exact types and values, as a set); lower facts are compared by
identity, which holds exactly when their own stratum was reused too (a re-evaluated stratum
counts as changed even if it found the same facts: checking that strictly would cost about as
much as evaluating the strata above it).
"""

from __future__ import annotations

import marshal
from collections.abc import Iterable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .store import BeliefSet, FactStore, PerceptIndex
    from .terms import Percept


class TypeSig:
    """The percepts of one type in one cycle, comparable with another cycle's (``same``).

    Two cycles' percepts are the same when they are equal as sets (order and duplicates do not
    matter to inference) *and* each value has the same type and bits: 3 == 3.0 and 0.0 == -0.0
    in Python, but a belief taking the value prints differently. The cheap set comparison comes
    first (it settles most changed cycles); only equal sets are compared strictly, encoding each
    percept with ``marshal`` format 2 (exact str, int, float, bool only; floats in binary; no
    shared references, so the encoding does not depend on how strings were built)."""

    __slots__ = ("tuples", "lax", "_strict")

    def __init__(self, percepts: Iterable[Percept]):
        self.tuples = [(p.type, p.id, p.attrs) for p in percepts]
        try:
            self.lax: frozenset | None = frozenset(self.tuples)
        except TypeError:  # an unhashable value: never the same
            self.lax = None
        self._strict: frozenset | None | bool = False  # False: not computed yet

    def strict(self) -> frozenset | None:
        """The exact encodings of the percepts (cached), or None if one cannot be encoded."""
        if self._strict is False:
            try:
                self._strict = frozenset([marshal.dumps(t, 2) for t in self.tuples])
            except ValueError:
                self._strict = None
        return self._strict  # type: ignore[return-value]

    def same(self, old: TypeSig) -> bool:
        """True when these percepts are exactly ``old``'s, up to order and duplicates."""
        if self is old:
            return True
        if self.lax is None or self.lax != old.lax:
            return False
        mine = self.strict()
        return mine is not None and mine == old.strict()


@dataclass(frozen=True, slots=True)
class InferStats:
    """How much one inference run evaluated: ``evaluated`` of ``strata`` strata."""

    strata: int
    evaluated: int

    @property
    def reused(self) -> int:
        """Strata whose facts were taken from the previous cycle."""
        return self.strata - self.evaluated


@dataclass(frozen=True, slots=True)
class Memo:
    """Last cycle's result: its FactStore, the signature of each percept type the program
    reads, each stratum's lower fact sets and, after an unchanged cycle, its BeliefSet.
    Immutable: a run replaces the memo, never edits it."""

    store: FactStore | None
    sigs: dict[str, TypeSig]
    deps: tuple[tuple, ...]
    beliefs: BeliefSet | None = None

    def with_beliefs(self, beliefs: BeliefSet) -> Memo:
        return replace(self, beliefs=beliefs)


EMPTY_MEMO = Memo(None, {}, ())


def unchanged_types(index: PerceptIndex, types: Iterable[str], memo: Memo) -> dict[str, bool]:
    """type -> True when this cycle's percepts of that type are exactly last cycle's."""
    return {t: t in memo.sigs and index.signature(t).same(memo.sigs[t]) for t in types}


def lower_facts(store: FactStore, deps: tuple[str, ...]) -> tuple:
    """The fact sets a stratum reads from lower strata (compared by identity: a set is the same
    object as last cycle's only when its stratum was reused, or both are the shared empty set)."""
    return tuple(store.get(p) for p in deps)
