"""Bottom-up inference to fixpoint over stratified concepts (seed 000, "Inference and Execution
Mechanisms"): strata in dependency order, one pass for a non-recursive stratum, semi-naive
iteration for a recursive one. Results depend only on the set of percepts, never their order."""

from __future__ import annotations

from collections.abc import Iterable

from .codegen import compile_clause
from .program import Program
from .store import BeliefSet, FactStore, PerceptIndex
from .terms import Percept


class Inference:
    """Compiled inference for one program; ``run`` is a pure function of the percepts."""

    def __init__(self, program: Program):
        self.program = program
        self.plan: list[tuple[tuple[str, ...], bool, list]] = []
        for preds, recursive in program.strata:
            clauses = [c for p in preds for c in program.concepts[p]]
            members = set(preds)
            rules = []
            for c in clauses:
                full = compile_clause(c)
                deltas = []
                if recursive:
                    deltas = [compile_clause(c, i) for i, r in enumerate(c.relations)
                              if not r.negated and r.pred in members]
                rules.append((c.head.pred, full, deltas))
            self.plan.append((preds, recursive, rules))

    def run(self, percepts: Iterable[Percept]) -> FactStore:
        """Every concept instance that holds for ``percepts``, as a FactStore."""
        index = percepts if isinstance(percepts, PerceptIndex) else PerceptIndex(percepts)
        store = FactStore()
        empty = FactStore()
        for _preds, recursive, rules in self.plan:
            new: dict[str, set] = {}
            for pred, full, _ in rules:
                out = new.setdefault(pred, set())
                full(index, store, empty, out.add)
            for pred, ts in new.items():
                if ts:
                    store.add(pred, ts)
            if recursive:
                self._fixpoint(index, store, new, rules)
        return store

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

    def beliefs(self, percepts: Iterable[Percept]) -> BeliefSet:
        """``run`` as a frozenset of Belief (carrying its FactStore)."""
        return BeliefSet(self.run(percepts))
