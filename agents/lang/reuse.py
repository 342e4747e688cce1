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

from collections.abc import Iterable
from dataclasses import dataclass, replace

from .store import BeliefSet, FactStore, PerceptIndex, TypeSig


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
