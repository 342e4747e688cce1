"""Truth maintenance: bringing one stratum's facts up to date with the changes below it.

A non-recursive stratum counts derivations (Gupta, Mumick and Subrahmanian's counting
algorithm): a fact holds while it has at least one. When the relations an element reads change,
the derivations gained and lost are those that join the change with the other elements, the
elements before it (in written order) read as they are now and those after it as they were
(``OldView``), so that each derivation is counted once. A negated element changes where its
literal's matches go from none to some (the negation stops holding) or back.

A recursive stratum (``above`` in Blocks World) uses delete-and-rederive (DRed): facts
derivable from a deleted tuple are deleted, with everything derived from them; those still
derivable another way come back; then insertions propagate semi-naively. Both give exactly
the facts a fixpoint from scratch gives (tests/lang/test_incremental.py)."""

from __future__ import annotations

from collections import Counter
from itertools import chain

from ..core.store import Delta, FactStore, OldView
from .codegen import HEAD


class Maintainer:
    """Updates strata in place: the percept relations ``edb``, the facts ``idb`` and the
    derivation counts of non-recursive concepts (``counts``)."""

    def __init__(self, edb: FactStore, idb: FactStore, counts: dict, est) -> None:
        self.edb, self.idb, self.counts, self.est = edb, idb, counts, est
        self.derivations = 0

    def views(self, rule, i: int, changes: dict) -> tuple:
        """Stores for a driver on element ``i``: before it as now, after it as before."""
        new = (self.idb, self.edb)
        elems = rule.elems
        if not any(elems[j].rel in changes for j in range(i + 1, len(elems))):
            return tuple(new[e.percept] for e in elems)  # (no OldView needed)
        old = (OldView(self.idb, changes), OldView(self.edb, changes))
        return tuple(old[e.percept] if j > i and e.rel in changes else new[e.percept]
                     for j, e in enumerate(elems))

    def flips(self, rule, j: int, d: Delta, changes: dict) -> tuple[list, list]:
        """Keys of negated element ``j`` whose negation became true, and became false."""
        neg = rule.negation(j)
        rel = rule.elems[j].rel
        keys = {neg.key(t) for t in chain(d.dels, d.ins) if neg.matches(t)}
        old = OldView(self.idb, changes)
        true, false = [], []
        for k in keys:
            now, before = _exists(self.idb, rel, neg, k), _exists(old, rel, neg, k)
            if before and not now:
                true.append(k)
            elif now and not before:
                false.append(k)
        return true, false

    # -- counting --------------------------------------------------------------------------
    def counting(self, stratum, changes: dict) -> dict:
        """Update a non-recursive stratum; its set-level change (pred -> Delta)."""
        minus: list = []
        plus: list = []
        for rule, vs, i, e in stratum.elems:
            d = changes.get(e.rel)
            if d:
                fn = vs[i].get(self.est)
                S = self.views(rule, i, changes)
                if e.negated:
                    gained, lost = self.flips(rule, i, d, changes)
                else:
                    gained, lost = d.ins, d.dels
                if lost:
                    fn(S, lost, minus.append)
                if gained:
                    fn(S, gained, plus.append)
        self.derivations += len(minus) + len(plus)
        pred = stratum.preds[0]
        return {pred: self.apply_counts(pred, minus, plus)}

    def apply_counts(self, pred: str, minus: list, plus: list) -> Delta | None:
        if minus == plus:
            return None
        sm, sp = set(minus), set(plus)
        if len(sm) == len(minus) and len(sp) == len(plus):  # no head derived twice
            moved = sm ^ sp
            if not moved:
                return None
            changes = [(h, 1 if h in sp else -1) for h in moved]
        else:
            cm, cp = Counter(minus), Counter(plus)
            changes = [(h, cp.get(h, 0) - cm.get(h, 0)) for h in sm | sp]
        counts = self.counts.setdefault(pred, {})
        dels, ins = [], []
        for h, dd in changes:
            if not dd:
                continue
            c = counts.get(h, 0)
            n = c + dd
            if n > 0:
                counts[h] = n
            elif n == 0:
                del counts[h]
            else:
                raise RuntimeError(f"inference of {pred}: {h} lost more derivations than it had")
            if c == 0:
                ins.append(h)
            elif n == 0:
                dels.append(h)
        self.idb.delete(pred, dels)
        self.idb.insert(pred, ins)
        return Delta(dels, ins) if dels or ins else None

    # -- delete and rederive -----------------------------------------------------------------
    def dred(self, stratum, changes: dict) -> dict:
        """Update a recursive stratum; its set-level change (pred -> Delta)."""
        preds = set(stratum.preds)
        idb = self.idb
        old = (OldView(idb, changes), OldView(self.edb, changes))
        new = (idb, self.edb)
        # 1. over-delete: everything with a derivation that used a deleted tuple
        lost = self._from_inputs(stratum, changes, old, deleted=True)
        doomed = {p: {h for h in lost[p] if h in idb.get(p)} for p in preds}
        delta = doomed
        while any(delta.values()):
            found = self._from_delta(stratum, delta, old)
            delta = {p: {h for h in found[p] if h not in doomed[p] and h in idb.get(p)}
                     for p in preds}
            for p in preds:
                doomed[p] |= delta[p]
        for p in preds:
            idb.delete(p, list(doomed[p]))
        # 2. rederive what is still derivable in one step
        back = {p: set() for p in preds}
        for rule, vs in stratum.rules:
            if doomed[rule.pred]:
                vs[HEAD].get(self.est)(_stores(rule, new), list(doomed[rule.pred]),
                                       back[rule.pred].add)
        for p in preds:
            idb.insert(p, list(back[p]))
        # 3. insert: new derivations from inserted tuples, then semi-naive
        found = self._from_inputs(stratum, changes, new, deleted=False)
        delta = {p: back[p] | self._fresh(p, found[p]) for p in preds}
        added = {p: [h for h in delta[p] if h not in back[p]] for p in preds}
        while any(delta.values()):
            found = self._from_delta(stratum, delta, new)
            delta = {p: self._fresh(p, found[p]) for p in preds}
            for p in preds:
                added[p] += delta[p]
        out = {}
        for p in preds:
            dels = [h for h in doomed[p] if h not in idb.get(p)]
            ins = [h for h in added[p] if h not in doomed[p]]
            out[p] = Delta(dels, ins) if dels or ins else None
        return out

    def _fresh(self, pred: str, found: list) -> set:
        have = self.idb.get(pred)
        fresh = {h for h in found if h not in have}
        self.idb.insert(pred, list(fresh))
        return fresh

    def _from_inputs(self, stratum, changes: dict, stores: tuple, deleted: bool) -> dict:
        """Heads derived with a tuple deleted from (inserted into) a relation below."""
        found: dict = {p: [] for p in stratum.preds}
        for rule, vs in stratum.rules:
            for i, e in enumerate(rule.elems):
                d = changes.get(e.rel)
                if not d or e.rel in found:
                    continue
                if e.negated:
                    true, false = self.flips(rule, i, d, changes)
                    drv = false if deleted else true
                else:
                    drv = d.dels if deleted else d.ins
                if drv:
                    vs[i].get(self.est)(_stores(rule, stores), drv, found[rule.pred].append)
        self.derivations += sum(map(len, found.values()))
        return found

    def _from_delta(self, stratum, delta: dict, stores: tuple) -> dict:
        """Heads derived with one of the stratum's own facts in ``delta`` (semi-naive)."""
        found: dict = {p: [] for p in stratum.preds}
        for rule, vs in stratum.rules:
            for i, e in enumerate(rule.elems):
                drv = delta.get(e.rel) if not e.negated else None
                if drv:
                    vs[i].get(self.est)(_stores(rule, stores), list(drv), found[rule.pred].append)
        self.derivations += sum(map(len, found.values()))
        return found


def _stores(rule, stores: tuple) -> tuple:
    """The store for each element: ``stores`` is (concept facts, percept relations)."""
    return tuple(stores[e.percept] for e in rule.elems)


def _exists(store, rel, neg, k: tuple) -> bool:
    """Some tuple of ``rel`` matches a negated literal with key ``k``."""
    if neg.keys:
        seq = store.index(rel, neg.keys).get(k, ())
    else:
        seq = store.get(rel)
    if not neg.same:
        return bool(seq)
    return any(neg.matches(t) for t in seq)
