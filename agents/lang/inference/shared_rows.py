"""Percepts whose unchanged rows are shared from cycle to cycle, read without reading them again.

The bus decodes a row it has seen on the same key last cycle, byte for byte, to the very same
list object (bus/rows.py; docs/bus.md, "Packed rows"), and nobody mutates a decoded row. A
caller that gives the engine such percepts wraps them in ``SharedRows``; the engine then takes
a row that is the same object as one of last cycle's as unchanged, strictly (the same bytes are
the same values of the same types), without reading its values: the cycle's grouping by type
is last cycle's with the new rows put in place (``Framer``), a type's columns are last cycle's
with only the new rows read and checked (``read_changed``), and the executive's Percept
objects are last cycle's but for the new rows (``SharedPercepts``). Plain lists are always
read in full: a caller may have changed them in place.
"""

from __future__ import annotations

from itertools import compress
from math import copysign
from operator import is_not

from ..core.columns import ATOMS, ID, Cols, plainly_valid, read_cols
from ..core.intake import Frame, frame_of
from ..core.terms import Percept, check_row


class SharedRows(tuple):
    """One cycle's percept rows (neutral lists or tuples) that nobody mutates; a row that is
    the same object as one of the previous SharedRows' is unchanged."""

    __slots__ = ()


class Framer:
    """Makes each cycle's Frame, reusing last cycle's grouping when the percepts are
    SharedRows of the same length, at most half of them new, the new ones of the same types."""

    def __init__(self) -> None:
        self.items: SharedRows | None = None
        self.frame: Frame | None = None
        self.where: list | None = None  # per position: (type, index in its group)

    def frame_of(self, percepts: object) -> Frame:
        if not isinstance(percepts, SharedRows):
            self.items = self.frame = self.where = None
            return frame_of(percepts)
        frame = self._patched(percepts) if self.items is not None else None
        if frame is None:
            frame = frame_of(percepts)
            frame.shared = True
            self.where = None
        self.items, self.frame = percepts, frame
        return frame

    def _patched(self, items: SharedRows) -> Frame | None:
        """Last cycle's grouping with this cycle's new rows in place, and for each type with
        new rows (last cycle's list, the positions of the new rows in it); None when the new
        rows do not fit (another length, more than half new, another type at a position)."""
        old, n = self.items, len(items)
        if n != len(old) or _mostly_new(items, old):
            return None
        at = list(compress(range(n), map(is_not, items, old)))
        prev = self.frame
        if len(at) * 2 > n:
            return None
        if not at:
            return Frame(prev.groups, shared=True, patched={})
        where = self.where
        if where is None:
            where = self.where = _positions(prev.groups, old)
            if where is None:
                return None
        groups = dict(prev.groups)
        patched: dict[str, tuple[list, list[int]]] = {}
        for i in at:
            row = items[i]
            t, j = where[i]
            if row.__class__ not in _SEQS or not row or row[0] != t \
                    or row[0].__class__ is not str:
                return None
            got = patched.get(t)
            if got is None:
                got = patched[t] = (prev.groups[t], [])
                groups[t] = list(got[0])
            groups[t][j] = row
            got[1].append(j)
        return Frame(groups, shared=True, patched=patched)


_SEQS = (list, tuple)
_PROBE = 32  # rows sampled first: when most of them are new, the rest are not compared


def _mostly_new(items: SharedRows, old: SharedRows) -> bool:
    """True when more than half of a sample of rows spread over the message are new (each
    comparison touches a row: all of them are compared only when most are kept)."""
    step = max(1, len(items) // _PROBE)
    sample = items[::step]
    return sum(map(is_not, sample, old[::step])) * 2 > len(sample)


def _positions(groups: dict, items: SharedRows) -> list | None:
    """For each position of ``items``: (its type, its index in the type's group); None if the
    groups do not hold the rows in that order."""
    seen = {t: 0 for t in groups}
    where = []
    for row in items:
        t = row[0]
        j = seen[t]
        if groups[t][j] is not row:
            return None
        where.append((t, j))
        seen[t] = j + 1
    return where


def new_since(frame: Frame, t: str, before: list | None) -> list[int] | None:
    """Positions of the rows of type ``t`` in ``frame`` that are new since ``before`` (an
    earlier cycle's rows of ``t``): [] when the frame holds that very list, those patched in
    when the frame was patched from it, None when the frame's rows are not ``before``'s
    (then every row must be read)."""
    if before is None or frame.patched is None:
        return None
    if frame.groups[t] is before:
        return []
    base = frame.patched.get(t)
    return base[1] if base is not None and base[0] is before else None


def read_changed(rows: list, old: Cols, at: list[int]) -> Cols | None:
    """``rows`` by column, when they are ``old.rows`` but for the new rows at positions ``at``
    (ascending): only those are read and checked (a row of the same names, values str, int or
    float, ids still distinct). None when that does not hold: the caller reads every row."""
    n = old.n
    if not at:
        return Cols(n, old.names, old.vals, old.types, old.kinds, set(old.vals), True, rows)
    width = 2 + 2 * len(old.names)
    for i in at:
        row = rows[i]
        if len(row) != width or tuple(row[2::2]) != old.names:
            return None
    vals, types, kinds, same = {}, {}, {}, set()
    for c, a in enumerate((ID, *old.names)):
        col, ts = list(old.vals[a]), list(old.types[a])
        strict = True
        for i in at:
            v = rows[i][1 + 2 * c]
            t = v.__class__
            if t not in ATOMS:
                return None
            w = col[i]
            if strict and (t is not ts[i] or v != w or
                           (t is float and v == 0 and copysign(1.0, v) != copysign(1.0, w))):
                strict = False
            col[i], ts[i] = v, t
        if strict:
            vals[a], types[a], kinds[a] = old.vals[a], old.types[a], old.kinds[a]
            same.add(a)
            continue
        vals[a], types[a] = tuple(col), ts
        kinds[a] = frozenset(ts)
    same_ids = ID in same or vals[ID] == old.ids
    if not same_ids and len(set(vals[ID])) != n:
        return None
    return Cols(n, old.names, vals, types, kinds, same, same_ids, rows)


class SharedPercepts:
    """The executive's Percept objects of shared rows (``Frame.cache`` for ``PerceptIndex``):
    a type's rows unchanged since the cycle its Percepts were last asked for keep them, and in a
    patched frame only the new rows get new ones."""

    def __init__(self) -> None:
        self.last: dict[str, tuple[list, list[Percept]]] = {}
        self.frame: Frame | None = None

    def bind(self, frame: Frame) -> SharedPercepts:
        """This cycle's frame is the one asked about from now on."""
        self.frame = frame
        return self

    def percepts(self, t: str, rows: list) -> list[Percept]:
        prev = self.last.get(t)
        at = new_since(self.frame, t, prev[0]) if prev is not None else None
        if at is None:
            out = list(map(Percept.of_row, rows))
        elif not at:
            return prev[1]
        else:
            out = list(prev[1])
            for j in at:
                out[j] = Percept.of_row(rows[j])
        self.last[t] = (rows, out)
        return out


def check_new_rows(frame: Frame) -> None:
    """Check the rows a patched frame holds that were not in last cycle's (raises LangError
    naming the percept); the others were checked when they came."""
    for t, (_, at) in frame.patched.items():
        _check_at(frame.groups[t], at)


def check_rows(frame: Frame, types: list[str], kept: dict[str, list]) -> None:
    """Check the rows of ``types`` (raises LangError naming a bad percept), except the shared
    rows taken in last cycle: a type whose rows are ``kept[type]`` needs no check, one patched
    from them only its new rows. Checked at once in C (``columns.plainly_valid``), row by row
    only where that is not clear."""
    for t in types:
        at = new_since(frame, t, kept.get(t))
        rows = frame.groups[t] if at is None else [frame.groups[t][j] for j in at]
        if not plainly_valid(rows):
            for row in rows:
                check_row(row)


def _check_at(rows: list, at: list[int]) -> None:
    for j in at:
        check_row(rows[j])


def read_cols_of(rows: list, old: Cols | None, frame: Frame, t: str) -> Cols | None:
    """``columns.read_cols`` of type ``t``'s ``rows`` in ``frame``, reading only the new rows
    when the frame was patched from the rows ``old`` was read from (``Framer``)."""
    at = new_since(frame, t, old.rows) if old is not None else None
    got = read_changed(rows, old, at) if at is not None else None
    if got is not None:
        return got
    got = read_cols(rows, old)
    if got is not None and frame.shared:
        got.rows = rows
    return got
