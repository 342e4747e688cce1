"""Bottom-up inference to fixpoint over stratified concepts (seed 000, "Inference and Execution
Mechanisms"): strata in dependency order, one pass for a non-recursive stratum, semi-naive
iteration for a recursive one. Results depend only on the set of percepts, never their order.

Work is reused across cycles per stratum (see ``reuse.py``): a stratum whose inputs (percepts of
the types its clauses read, facts of the lower concepts it reads) equal last cycle's keeps last
cycle's facts instead of being evaluated again; the result is the same as from scratch."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from .codegen import compile_clause
from .program import Program
from .reuse import EMPTY_MEMO, InferStats, Memo, lower_facts, unchanged_types
from .store import BeliefSet, FactStore, PerceptIndex
from .terms import Percept


@dataclass(frozen=True, slots=True)
class Stratum:
    """One SCC of concepts, compiled: its rules and what it reads from outside itself."""

    preds: tuple[str, ...]
    recursive: bool
    rules: tuple  # (head pred, full rule, delta rules)
    types: tuple[str, ...]  # percept types its clauses match
    deps: tuple[str, ...]  # concepts of lower strata its clauses read (positive or negated)


def compile_stratum(program: Program, preds: tuple[str, ...], recursive: bool) -> Stratum:
    """Compile the clauses of one SCC (delta variants for semi-naive iteration if recursive)."""
    clauses = [c for p in preds for c in program.concepts[p]]
    members = set(preds)
    rules = []
    for c in clauses:
        deltas = []
        if recursive:
            deltas = [compile_clause(c, i) for i, r in enumerate(c.relations)
                      if not r.negated and r.pred in members]
        rules.append((c.head.pred, compile_clause(c), deltas))
    types = sorted({pp.type for c in clauses for pp in c.percepts})
    deps = sorted({r.pred for c in clauses for r in c.relations} - members)
    return Stratum(tuple(preds), recursive, tuple(rules), tuple(types), tuple(deps))


def _reusable(stratum: Stratum, memo: Memo, i: int, same: dict[str, bool],
              facts: tuple) -> bool:
    """True when stratum ``i`` reads exactly last cycle's percepts and lower fact sets."""
    if memo.store is None or not all(same[t] for t in stratum.types):
        return False
    return all(a is b for a, b in zip(facts, memo.deps[i], strict=True))


class Inference:
    """Compiled inference for one program; ``run`` is a pure function of the percepts.

    It holds one mutable attribute besides compiled code: ``memo``, last cycle's stratum inputs
    and facts, replaced (never changed in place) by each run. The memo never changes a result,
    only how much is recomputed: a stratum is reused only when its inputs are exactly last
    cycle's, and then evaluating it would give exactly last cycle's facts. ``last_stats`` says
    how many strata the last run evaluated (for tests and benchmarks). Runs from several
    threads stay correct (each reads the memo once and replaces it whole; a memo is consistent
    in itself), though ``last_stats`` is then the last finisher's."""

    def __init__(self, program: Program):
        self.program = program
        self.plan = [compile_stratum(program, preds, rec) for preds, rec in program.strata]
        self.types = sorted({t for s in self.plan for t in s.types})
        self.memo: Memo = EMPTY_MEMO
        self.last_stats = InferStats(len(self.plan), 0)
        self._base: tuple = ()                # the base facts of the last run
        self._base_sets: dict[str, set] = {}  # pred -> its base facts (same objects while equal)

    def forget(self) -> None:
        """Drop the memo, so that the next run evaluates every stratum (from-scratch timings)."""
        self.memo = EMPTY_MEMO

    def run(self, percepts: Iterable[Percept], base: tuple[tuple, ...] = ()) -> FactStore:
        """Every concept instance that holds for ``percepts`` and the ``base`` facts
        ((pred, arg, ...) tuples: the agent's world model, asserted by SCS bodies, seed 002),
        as a FactStore (read-only: its fact sets may be shared with the previous and next
        cycles' stores). Base facts are facts before the first stratum; a concept that has
        clauses too gets its inferred instances joined with them."""
        index = percepts if isinstance(percepts, PerceptIndex) else PerceptIndex(percepts)
        if base != self._base:
            self._set_base(base)
        memo = self.memo
        same = unchanged_types(index, self.types, memo)
        store = FactStore()
        for pred, facts in self._base_sets.items():
            store.facts[pred] = set(facts) if pred in self.program.concepts else facts
        deps = []
        evaluated = 0
        for i, stratum in enumerate(self.plan):
            facts = lower_facts(store, stratum.deps)
            if _reusable(stratum, memo, i, same, facts):
                store.adopt(memo.store, stratum.preds)
            else:
                self._evaluate(stratum, index, store)
                evaluated += 1
            deps.append(facts)
        if not evaluated and memo.store is not None:
            store = memo.store  # every stratum reused: same facts, keep the built indexes
        sigs = {t: index.signature(t) for t in self.types}
        self.memo = Memo(store, sigs, tuple(deps), memo.beliefs if store is memo.store else None)
        self.last_stats = InferStats(len(self.plan), evaluated)
        return store

    def _set_base(self, base: tuple[tuple, ...]) -> None:
        """New base facts: every stratum may read them, so nothing of the memo is reused."""
        sets: dict[str, set] = {}
        for row in base:
            sets.setdefault(row[0], set()).add(tuple(row[1:]))
        self._base, self._base_sets, self.memo = tuple(base), sets, EMPTY_MEMO

    def _evaluate(self, stratum: Stratum, index: PerceptIndex, store: FactStore) -> None:
        """Add the facts of one stratum to ``store``."""
        empty = FactStore()
        new: dict[str, set] = {}
        for pred, full, _ in stratum.rules:
            out = new.setdefault(pred, set())
            full(index, store, empty, out.add)
        for pred, ts in new.items():
            if ts:
                store.add(pred, ts)
        if stratum.recursive:
            self._fixpoint(index, store, new, stratum.rules)

    @staticmethod
    def _fixpoint(index: PerceptIndex, store: FactStore, delta: dict[str, set], rules) -> None:
        """Semi-naive iteration: each round joins at least one literal against the last delta."""
        while any(delta.values()):
            dstore = FactStore({p: ts for p, ts in delta.items() if ts})
            found: dict[str, set] = {}
            for pred, _, deltas in rules:
                out = found.setdefault(pred, set())
                for rule in deltas:
                    rule(index, store, dstore, out.add)
            delta = {}
            for pred, ts in found.items():
                fresh = ts - store.get(pred)
                if fresh:
                    delta[pred] = fresh
                    store.add(pred, fresh)

    def beliefs(self, percepts: Iterable[Percept], base: tuple[tuple, ...] = ()) -> BeliefSet:
        """``run`` as a frozenset of Belief (carrying its FactStore); last cycle's BeliefSet
        itself when every stratum was reused."""
        store = self.run(percepts, base)
        memo = self.memo
        if memo.beliefs is not None and memo.beliefs.store is store:
            return memo.beliefs
        beliefs = BeliefSet(store)
        if memo.store is store and not self.last_stats.evaluated:
            # kept only when nothing changed: holding every cycle's beliefs for one more cycle
            # costs garbage-collection time when the percepts keep changing
            self.memo = memo.with_beliefs(beliefs)
        return beliefs
