"""A percept type's rows read by column, and what changed since last cycle, strictly.

When every row of a type has the same attributes in the same order and the ids are distinct
(the usual case: one producer, one layout), the rows are transposed with one ``zip`` and each
column is compared with last cycle's as a whole, in C: a column that is equal (and of the same
value types) costs no per-object work, and a changed column gives the changed positions. The
percept relations the program reads (``(type, attrs)``: id and the attribute values) change only
at those positions. "Equal" is strict: ``3`` and ``3.0``, or ``0.0`` and ``-0.0``, are equal to
``==`` but print differently in a belief, so a change of type or zero sign counts as a change.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import chain, compress, repeat
from math import copysign
from operator import is_, is_not, itemgetter, ne, not_

ATOMS = frozenset({str, int, float})
ID = None  # the column of ids (no attribute name is None)


class Cols:
    """One type's rows of one cycle by column: ``vals[attr]`` (tuples, row order; the ids are
    the column ``ID``), the exact type of every value (``types[attr]``: lists) and the set of
    types in each column (``kinds[attr]``)."""

    __slots__ = ("n", "names", "ids", "vals", "types", "kinds", "same", "same_ids", "rows")

    def __init__(self, n, names, vals, types, kinds, same, same_ids, rows=None):
        self.n = n
        self.names: tuple[str, ...] = names
        self.ids: tuple = vals[ID]
        self.vals: dict[str | None, tuple] = vals
        self.types: dict[str | None, list] = types
        self.kinds: dict[str | None, frozenset] = kinds
        self.same: set = same  # columns found strictly equal to the previous Cols'
        self.same_ids = same_ids  # ids equal (==) to the previous Cols' ids, in the same order
        self.rows = rows  # the rows read, when they are shared rows (shared_rows.py); else None


_STRS = frozenset({str})


def read_cols(rows: list, old: Cols | None) -> Cols | None:
    """``rows`` (of one type) by column, every value checked to be str, int or float; None when
    the rows are irregular (different lengths or names, repeated ids or names, other value
    types): the caller then checks them row by row and reads them one by one. ``old``: the
    previous cycle's columns of the type, which make the checks cheaper."""
    cols = _transpose(rows)
    if cols is None:
        return None
    k = len(cols)
    n = len(rows)
    if k < 2 or k % 2:
        return None
    names = []
    for c in cols[2::2]:
        first = c[0]
        if first.__class__ is not str or c.count(first) != n:
            return None
        names.append(first)
    names_t = tuple(names)
    if len(set(names_t)) != len(names_t):
        return None
    if old is not None and old.names != names_t:
        old = None
    ids = cols[1]
    same_ids = old is not None and ids == old.ids
    vals, types, kinds, same = {}, {}, {}, set()
    for a, col in zip((ID, *names_t), cols[1::2], strict=True):
        vals[a] = col
        if old is not None:
            was = old.kinds[a]
            if was == _STRS and same_ids and (a is ID or col == old.vals[a]):
                types[a], kinds[a] = old.types[a], was  # equal to last cycle's strs: strs
                same.add(a)
                continue
            ts = list(map(type, col))
            if ts == old.types[a]:
                types[a], kinds[a] = old.types[a], was
                continue
        else:
            ts = list(map(type, col))
        got = frozenset(ts)
        if not got <= ATOMS:
            return None
        types[a], kinds[a] = ts, got
    if not same_ids and len(set(ids)) != n:
        return None
    return Cols(n, names_t, vals, types, kinds, same, same_ids)


def plainly_valid(rows: list) -> bool:
    """True when ``rows`` (of any types, each a list or tuple led by its type's name) are all
    ``[type, id, name, value, ...]`` of an even length of at least 2 with the type and names of
    type str and ids and values of type str, int or float: what ``terms.check_row`` accepts,
    decided in three C-level passes over all the rows at once. False when that is not clear
    (a subclass of int, another length): the caller then checks the rows one by one."""
    if not rows:
        return True
    lens = set(map(len, rows))
    return min(lens) >= 2 and not any(n & 1 for n in lens) and \
        ATOMS.issuperset(map(type, chain.from_iterable(rows))) and \
        _STRS.issuperset(map(type, chain.from_iterable(map(_EVEN, rows))))


_EVEN = itemgetter(slice(0, None, 2))  # a row's type and attribute names


def _transpose(rows: list) -> list[tuple] | None:
    """The columns of ``rows``, or None if their lengths differ."""
    try:
        return list(zip(*rows, strict=True))
    except ValueError:
        return None


def changed(old: tuple, new: tuple, old_t, new_t, floats: bool) -> list[int]:
    """Positions (ascending) where aligned columns differ strictly (value, type, or zero sign);
    ``floats``: the new column may hold floats."""
    n = len(new)
    pos = [] if old == new else list(compress(range(n), map(ne, old, new)))
    more = []
    if old_t is not new_t and old_t != new_t:
        more = list(compress(range(n), map(is_not, old_t, new_t)))
    if floats and 0.0 in new:
        more += [i for i in compress(range(n), map(not_, new))
                 if new_t[i] is float and old_t[i] is float
                 and copysign(1.0, new[i]) != copysign(1.0, old[i])]
    if more:
        return sorted(set(pos).union(more))
    return pos


@dataclass(frozen=True, slots=True)
class Summary:
    """The values of some percept columns that can be equal to ``==`` yet print differently:
    ints, integral floats, and whether +0.0 / -0.0 occur."""

    ints: frozenset = frozenset()
    floats: frozenset = frozenset()
    pos0: bool = False
    neg0: bool = False

    def __or__(self, other: Summary) -> Summary:
        return Summary(self.ints | other.ints, self.floats | other.floats,
                       self.pos0 or other.pos0, self.neg0 or other.neg0)

    @property
    def mixed(self) -> bool:
        """True when two values are equal but of different type or zero sign (``3``, ``3.0``)."""
        return bool(self.ints & self.floats) or (self.pos0 and self.neg0)

    def clashes(self, new: Summary) -> bool:
        """True when a value here equals one in ``new`` of another type or zero sign."""
        return bool(self.ints & new.floats or self.floats & new.ints) or \
            (self.pos0 and new.neg0) or (self.neg0 and new.pos0)


EMPTY = Summary()


def summarize(vals: tuple | list, types: list, kinds: frozenset | None = None) -> Summary:
    """Summary of one column (``types``: each value's exact type; ``kinds``: their set)."""
    kinds = frozenset(types) if kinds is None else kinds
    if kinds == _STRS or not kinds:
        return EMPTY
    if kinds == _FLOATS:
        ints, fl = set(), vals
    elif kinds == _INTS:
        ints, fl = set(vals), ()
    else:
        ints = set(compress(vals, map(is_, types, repeat(int))))
        fl = list(compress(vals, map(is_, types, repeat(float))))
        if not kinds <= ATOMS:
            for v, t in zip(vals, types, strict=True):  # subclasses of int or float
                if t not in ATOMS:
                    if isinstance(v, float):
                        fl.append(v)
                    elif isinstance(v, int):
                        ints.add(v)
    floats = set(compress(fl, map(float.is_integer, fl)))
    pos0 = neg0 = False
    if 0.0 in floats:
        for z in compress(fl, map(not_, fl)):
            if copysign(1.0, z) > 0:
                pos0 = True
            else:
                neg0 = True
    if not ints and not floats:
        return EMPTY
    return Summary(frozenset(ints), frozenset(floats), pos0, neg0)


_FLOATS = frozenset({float})
_INTS = frozenset({int})


def summarize_values(values: list) -> Summary:
    """Summary of loose values (irregular rows, program constants)."""
    return summarize(values, list(map(type, values)))
