"""The percept relations a program reads, kept in step with the percepts cycle by cycle.

A percept pattern ``(block ?b xpos ?x ypos ?y)`` reads the relation ``("block", ("xpos",
"ypos"))`` of tuples ``(id, xpos, ypos)``, one per block having both attributes. Each cycle
``PerceptTracker.update`` gives the strict change (``Delta``) of every such relation: for a type
read by column (``columns.py``) only the objects whose id or one of the relation's attributes
changed, matched by id when objects appeared or disappeared; for irregular rows, the difference
of the whole relation. It also tells whether any two values clash (equal to ``==`` but of
another type or zero sign), which decides how inference applies the changes (``inference.py``).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from itertools import chain, compress, repeat
from math import copysign
from operator import is_, is_not, itemgetter, not_

from ..core.columns import (
    EMPTY,
    ID,
    Cols,
    Summary,
    changed,
    plainly_valid,
    summarize,
    summarize_values,
)
from ..core.intake import Frame
from ..core.store import Delta, FactStore
from .shared_rows import check_rows, read_cols_of


@dataclass(frozen=True, slots=True)
class PerceptChange:
    """This cycle's changes to the percept relations, and whether values clash: ``was_mixed``
    / ``mixed`` (last / this cycle's values hold a clash) and ``clash`` (a value of last cycle
    clashes with one of this cycle)."""

    deltas: dict
    was_mixed: bool
    mixed: bool
    clash: bool


class PerceptTracker:
    """Last cycle's percepts by column, and the strict changes of the relations ``rels``."""

    def __init__(self, rels: Iterable[tuple[str, tuple[str, ...]]], constants: Summary = EMPTY):
        self.rels_of: dict[str, list] = {}
        for r in sorted(set(rels)):
            self.rels_of.setdefault(r[0], []).append(r)
        self.read = {t: sorted({a for r in rs for a in r[1]}) for t, rs in self.rels_of.items()}
        self.cols: dict[str, Cols] = {}
        self.sums: dict[tuple, Summary] = {}
        self.constants = constants
        self.summary = constants
        self.kept: dict[str, list] = {}  # irregular type -> its shared rows last taken in

    def update(self, frame: Frame, edb: FactStore, extra: Summary = EMPTY) -> PerceptChange:
        """The changes from last cycle's percepts (as held in ``edb``) to ``frame``'s;
        ``extra``: the values of other facts joining inference (the world model)."""
        deltas: dict = {}
        sums_before = dict(self.sums)
        cols = self.cols
        # only the types the program reads are read by column; the others are only checked
        news = {t: read_cols_of(rows, cols.get(t), frame, t)
                for t, rows in frame.groups.items() if t in self.rels_of}
        unread = [t for t in frame.groups if t not in news]
        irregular = [t for t, c in news.items() if c is None]
        kept = self.kept if frame.shared else {}
        if not frame.checked:  # every check before any change: a bad message changes nothing
            check_rows(frame, irregular + unread, kept)
        for t, new in news.items():
            rows, old = frame.groups[t], self.cols.get(t)
            if old is not None and (new is None or old.names != new.names):
                old = None
            if new is None:
                self.cols.pop(t, None)
                if rows is not kept.get(t):  # else: the same rows
                    self._irregular(t, rows, edb, deltas)
                continue
            self.cols[t] = new
            self._regular(t, old, new, edb, deltas)
        for t in self.rels_of:
            if t not in frame.groups:
                self.cols.pop(t, None)
                for rel in self.rels_of[t]:
                    diff_relation(rel, set(), edb, deltas)
                for a in (ID, *self.read[t]):
                    self.sums.pop((t, a), None)
        for t in [t for t in self.cols if t not in frame.groups]:
            del self.cols[t]
        if extra is not self.sums.get(None, EMPTY):
            self.sums[None] = extra
        was = self.summary
        if self.sums != sums_before:
            now = self.constants
            for s in self.sums.values():
                if s is not EMPTY:
                    now = now | s
            self.summary = now
        now = self.summary
        self.kept = {t: frame.groups[t] for t in irregular + unread} if frame.shared else {}
        return PerceptChange(deltas, was.mixed, now.mixed, now is not was and was.clashes(now))

    # -- one type ------------------------------------------------------------------------
    def _regular(self, t: str, old: Cols | None, new: Cols, edb: FactStore, deltas: dict) -> None:
        rels = self.rels_of[t]
        if old is None:
            for rel in rels:
                attrs = rel[1]
                tuples = set(_rows_of(new, attrs)) if _has(new, attrs) else set()
                diff_relation(rel, tuples, edb, deltas)
            self._summaries(t, new, self.read[t])
            return
        if new.same_ids:
            dead, born = [], []
            o_at = n_at = o_pick = n_pick = None
        else:
            where = dict(zip(old.ids, range(old.n), strict=True))
            at = list(map(where.get, new.ids))
            kept = list(map(is_not, at, repeat(None)))
            n_at = list(compress(range(new.n), kept))
            o_at = list(compress(at, kept))
            born = list(compress(range(new.n), map(is_, at, repeat(None))))
            alive = set(new.ids)
            dead = list(compress(range(old.n), map(not_, map(alive.__contains__, old.ids))))
            o_pick, n_pick = _picker(o_at), _picker(n_at)
        moves = {}
        for a in (ID, *self.read[t]):
            if a not in new.vals:
                continue
            if o_pick is None and a in new.same:
                moves[a] = []
                continue
            o, n, ot, nt = old.vals[a], new.vals[a], old.types[a], new.types[a]
            if o_pick is not None:
                o, n, ot, nt = o_pick(o), n_pick(n), o_pick(ot), n_pick(nt)
            moves[a] = changed(o, n, ot, nt, float in new.kinds[a])
        hot = {a for a, m in moves.items() if m}
        if not (hot or dead or born):
            return
        every = dead or born or ID in hot
        for rel in rels:
            attrs = rel[1]
            if not (every or not hot.isdisjoint(attrs)) or not _has(new, attrs):
                continue
            ks = _union([moves[ID], *(moves[a] for a in attrs)])
            if o_pick is None:
                pick = _picker(ks)  # the same positions, last cycle's rows and this cycle's
                deltas[rel] = Delta(_rows_at(old, attrs, ks, pick), _rows_at(new, attrs, ks, pick))
                continue
            gone = dead + [o_at[k] for k in ks]
            came = born + [n_at[k] for k in ks]
            deltas[rel] = Delta(_rows_at(old, attrs, gone), _rows_at(new, attrs, came))
        if dead or born or ID in hot:
            self._summaries(t, new, self.read[t])
        else:
            self._summaries(t, new, hot, ids=False)

    def _irregular(self, t: str, rows: list, edb: FactStore, deltas: dict) -> None:
        maps = [(r[1], dict(zip(r[2::2], r[3::2], strict=True))) for r in rows]
        for rel in self.rels_of[t]:
            attrs = rel[1]
            tuples = {(i, *(m[a] for a in attrs)) for i, m in maps if all(a in m for a in attrs)}
            diff_relation(rel, tuples, edb, deltas)
        self.sums[(t, ID)] = summarize_values([i for i, _ in maps])
        for a in self.read[t]:
            self.sums[(t, a)] = summarize_values([m[a] for _, m in maps if a in m])

    def _summaries(self, t: str, c: Cols, attrs: Iterable[str], ids: bool = True) -> None:
        if ids:
            self.sums[(t, ID)] = summarize(c.ids, c.types[ID], c.kinds[ID])
        for a in attrs:
            if a in c.vals:
                self.sums[(t, a)] = summarize(c.vals[a], c.types[a], c.kinds[a])
            else:
                self.sums.pop((t, a), None)


def check_frame(frame: Frame) -> None:
    """Check every value of ``frame`` (raises LangError naming a bad percept)."""
    if frame.checked:  # Percept objects: nothing to check
        return
    if not plainly_valid(list(chain.from_iterable(frame.groups.values()))):
        for t, rows in frame.groups.items():  # find the bad ones
            if not plainly_valid(rows):
                frame.check([t])
    frame.checked = True


def _union(lists: list[list[int]]) -> list[int]:
    """Sorted union of sorted position lists (usually one or none is non-empty)."""
    full = [x for x in lists if x]
    if len(full) <= 1:
        return full[0] if full else []
    return sorted(set().union(*full))


def _has(c: Cols, attrs: tuple[str, ...]) -> bool:
    return all(a in c.vals for a in attrs)


def _rows_of(c: Cols, attrs: tuple[str, ...]):
    return zip(c.ids, *(c.vals[a] for a in attrs), strict=True)


def _picker(positions: list[int]):
    """Function taking the items at ``positions`` of a sequence, as a tuple."""
    if not positions:
        return lambda seq: ()
    if len(positions) == 1:
        p = positions[0]
        return lambda seq: (seq[p],)
    return itemgetter(*positions)


def _rows_at(c: Cols, attrs: tuple[str, ...], positions: list[int], pick=None) -> list:
    """The rows (id, *attrs) of ``c`` at ``positions`` (``pick``: their picker, if made)."""
    if not positions:
        return []
    if pick is None:
        pick = _picker(positions)
    return list(zip(pick(c.ids), *(pick(c.vals[a]) for a in attrs), strict=True))


def diff_relation(rel: object, new: set, edb: FactStore, deltas: dict) -> None:
    """Put in ``deltas`` the strict change from ``rel``'s tuples in ``edb`` to ``new``."""
    cur = edb.get(rel)
    if not cur:
        if new:
            deltas[rel] = Delta([], list(new))
        return
    dels, ins = list(cur - new), list(new - cur)
    stored = dict(zip(cur, cur, strict=True))
    for t in new:
        o = stored.get(t)
        if o is not None and o is not t and not _strictly_same(o, t):
            dels.append(o)
            ins.append(t)
    if dels or ins:
        deltas[rel] = Delta(dels, ins)


def _strictly_same(a: tuple, b: tuple) -> bool:
    for x, y in zip(a, b, strict=True):
        if x.__class__ is not y.__class__:
            return False
        if x.__class__ is float and x == 0 and copysign(1.0, x) != copysign(1.0, y):
            return False
    return True
