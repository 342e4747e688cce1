"""Bottom-up inference over stratified concepts (seed 000, "Inference and Execution
Mechanisms"), kept up to date cycle by cycle: work follows what changed.

The first run (and a run after ``forget``, or one where most percept tuples changed) evaluates
every stratum from scratch: one pass for a non-recursive stratum, counting derivations,
semi-naive iteration for a recursive one. Later
runs read which percept relations changed (``tracker.py``: per object and attribute, strictly)
and bring each stratum that reads a changed relation up to date (``maintain.py``); a stratum
that reads nothing changed costs nothing. The facts are always exactly those a run from
scratch gives (tests/lang/test_incremental.py). Results never depend on percept order.

Values equal to ``==`` but of another type or zero sign (``3``, ``3.0``) need care, because a
fact keeps the variant it was derived with: when last cycle's and this cycle's values clash the
changes are applied in two passes (deletions, then insertions), and after a cycle that held
clashing values itself (whose results depend on evaluation order even from scratch) the facts
are computed from scratch again."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

from ..core.columns import EMPTY, summarize_values
from ..core.intake import Frame, PerceptCache
from ..core.program import Program
from ..core.store import BeliefSet, Delta, FactStore
from ..core.terms import Belief, Var
from .base import BASE, BaseFacts, base_rule
from .codegen import Estimator, variants
from .maintain import Maintainer
from .rules import Rule
from .shared_rows import Framer
from .tracker import PerceptTracker

_new_tuple = tuple.__new__
_REPLAN_EVERY = 8  # runs between looks at whether join plans were made for other sizes
_SCRATCH_ABOVE = 256  # percept tuples above which a change of most of them starts from scratch


@dataclass(frozen=True, slots=True)
class InferStats:
    """What one run did. ``mode``: "scratch" (every stratum evaluated), "changes" (strata
    reading a changed relation brought up to date), "two-pass" (the same, deletions first) or
    "unchanged" (no percept relation changed: nothing evaluated). ``evaluated`` of ``strata``
    strata did any work; ``percept_changes`` tuples entered or left percept relations;
    ``derivations`` head derivations were computed; ``changed`` names the concepts whose
    facts changed."""

    strata: int
    evaluated: int
    mode: str = "scratch"
    percept_changes: int = 0
    derivations: int = 0
    changed: tuple[str, ...] = ()

    @property
    def reused(self) -> int:
        """Strata that did no work (their facts carried over unchanged)."""
        return self.strata - self.evaluated


@dataclass(frozen=True, slots=True)
class Stratum:
    """One SCC of concepts: its rules (with their compiled variants) and what it reads."""

    preds: tuple[str, ...]
    recursive: bool
    rules: tuple  # ((Rule, variants), ...)
    reads: frozenset  # relations read from below (percept relations and lower concepts)
    elems: tuple = ()  # ((Rule, variants, position, Elem), ...) of every rule, in order


def build_strata(program: Program) -> list[Stratum]:
    """The program's strata, each concept with its clauses and its base rule."""
    out = []
    for preds, recursive in program.strata:
        rules = [*(r for p in preds for r in map(Rule.of, program.concepts[p])),
                 *(base_rule(p, program.arity[p]) for p in preds)]
        rules = tuple((r, variants(r)) for r in rules)
        reads = frozenset(rel for r, _ in rules for rel in r.reads()) - set(preds)
        elems = tuple((r, vs, i, e) for r, vs in rules for i, e in enumerate(r.elems))
        out.append(Stratum(tuple(preds), recursive, rules, reads, elems))
    return out


def _constants(strata: list[Stratum]) -> list:
    return [a for s in strata for r, _ in s.rules for a in r.head if not isinstance(a, Var)]


class Inference:
    """Compiled inference for one program, holding last cycle's percept relations, facts and
    derivation counts; ``run`` is a pure function of the percepts all the same (the state
    only saves work). ``last_stats`` tells what the last run did. Not for concurrent use."""

    def __init__(self, program: Program):
        self.program = program
        self.plan = build_strata(program)
        self.last_stats = InferStats(len(self.plan), 0)
        self.runs = 0
        self.forget()

    def forget(self) -> None:
        """Drop what was carried over, so that the next run evaluates every stratum."""
        rels = {e.rel for s in self.plan for r, _ in s.rules for e in r.elems
                if e.percept and e.rel[0] != BASE}
        consts = _constants(self.plan)
        self.tracker = PerceptTracker(rels, summarize_values(consts) if consts else EMPTY)
        self.percepts = PerceptCache(self.tracker.cols)
        self.base = BaseFacts(self.program.concepts)
        self.edb = FactStore()
        self.idb = FactStore()
        self.counts: dict[str, dict] = {}
        self.fresh = True
        self.frame: Frame | None = None
        self.framer = Framer()
        self._beliefs: set = set()
        self._result: BeliefSet | None = None

    def run(self, percepts: Iterable, base: tuple[tuple, ...] = ()) -> FactStore:
        """Every concept instance that holds for ``percepts`` (neutral lists, Percepts, a
        PerceptIndex or a Frame) and the ``base`` facts ((pred, arg, ...) tuples: the agent's
        world model, asserted by SCS bodies, seed 002; see ``base.py``), as the live FactStore
        (valid until the next run). When the garbage collector runs is the caller's policy
        (bus/collector.py: between cycles), not the engine's: a run makes no reference cycles."""
        frame = self.frame = self.framer.frame_of(percepts)
        summary = self.base.summary_of(base)
        change = self.tracker.update(frame, self.edb, summary)
        frame.cache = self.percepts
        deltas = change.deltas
        self.base.update(base, self.edb, self.idb, deltas)
        moved = sum(len(d.dels) + len(d.ins) for d in deltas.values())
        if self.fresh or (change.was_mixed and not change.mixed) or self._most(moved):
            self._apply(deltas)
            self._scratch()
            return self.idb
        if not deltas:
            self.last_stats = InferStats(len(self.plan), 0, "unchanged")
            return self.idb
        self.runs += 1
        est = Estimator(self.edb, self.idb, check=self.runs % _REPLAN_EVERY == 0)
        m = Maintainer(self.edb, self.idb, self.counts, est)
        if change.clash:
            passes = [{r: Delta(d.dels, []) for r, d in deltas.items() if d.dels},
                      {r: Delta([], d.ins) for r, d in deltas.items() if d.ins}]
            mode = "two-pass"
        else:
            passes, mode = [deltas], "changes"
        evaluated, changed = set(), []
        for changes in passes:
            self._apply(changes)
            changed += [(r, d) for r, d in changes.items() if r.__class__ is str]
            for k, stratum in enumerate(self.plan):
                if stratum.reads.isdisjoint(changes):
                    continue
                evaluated.add(k)
                got = m.dred(stratum, changes) if stratum.recursive else \
                    m.counting(stratum, changes)
                for pred, d in got.items():
                    if d:
                        changes[pred] = d
                        changed.append((pred, d))
        if changed:
            self.idb.version += 1
            for pred, d in changed:
                self._beliefs.difference_update([_new_tuple(Belief, (pred, t)) for t in d.dels])
                self._beliefs.update([_new_tuple(Belief, (pred, t)) for t in d.ins])
            self._result = None
        names = tuple(sorted({p for p, _ in changed}))
        self.last_stats = InferStats(len(self.plan), len(evaluated), mode, moved, m.derivations,
                                     names)
        return self.idb

    def _most(self, moved: int) -> bool:
        """True when more than half the percept tuples changed (from scratch is cheaper)."""
        held = sum(map(len, self.edb.facts.values()))
        return held > _SCRATCH_ABOVE and moved > held

    def _apply(self, deltas: dict) -> None:
        """Apply the changes of percept and base relations (asserted-only predicates: facts)."""
        for rel, d in deltas.items():
            store = self.idb if rel.__class__ is str else self.edb
            store.delete(rel, d.dels)
            store.insert(rel, d.ins)

    def _scratch(self) -> None:
        """Evaluate every stratum from the percept relations alone."""
        idb = self.idb = FactStore()
        for pred, facts in self.base.plain().items():
            idb.insert(pred, list(facts))
        self.counts = {}
        est = Estimator(self.edb, idb)
        stores = (idb, self.edb)
        m = Maintainer(self.edb, idb, self.counts, est)
        derivations = 0
        for stratum in self.plan:
            found: dict = {p: [] for p in stratum.preds}
            for rule, vs in stratum.rules:
                vs[None].get(est)(tuple(stores[e.percept] for e in rule.elems), None,
                                  found[rule.pred].append)
            derivations += sum(map(len, found.values()))
            if not stratum.recursive:
                pred = stratum.preds[0]
                c = self.counts[pred] = Counter(found[pred])
                idb.insert(pred, list(c))
                continue
            delta = {p: m._fresh(p, found[p]) for p in stratum.preds}
            while any(delta.values()):
                found = m._from_delta(stratum, delta, stores)
                delta = {p: m._fresh(p, found[p]) for p in stratum.preds}
        self.fresh = False
        self._beliefs = {_new_tuple(Belief, (p, t)) for p, ts in idb.facts.items() for t in ts}
        self._result = None
        self.last_stats = InferStats(len(self.plan), len(self.plan), "scratch",
                                     sum(map(len, self.edb.facts.values())),
                                     derivations + m.derivations,
                                     tuple(sorted(p for p, ts in idb.facts.items() if ts)))

    def beliefs(self, percepts: Iterable, base: tuple[tuple, ...] = ()) -> BeliefSet:
        """``run`` as a frozenset of Belief carrying its FactStore; the same object as last
        cycle's when no fact changed."""
        self.run(percepts, base)
        if self._result is None:
            self._result = BeliefSet(self._beliefs, self.idb)
        return self._result
