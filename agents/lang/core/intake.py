"""Percepts entering the engine: neutral lists (as msgpack decodes them) or Percept objects,
checked once per message in a few C-level passes and grouped by type, without building a
Percept per object. Percept objects are built only when the executive asks for them
(``PerceptIndex``); inference reads the grouped rows by column (``columns.py``)."""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from itertools import count, groupby
from operator import itemgetter

from .columns import ID, changed
from .terms import Percept, check_row

MISSING = object()
_SEQS = frozenset({list, tuple})
_FIRST = itemgetter(0)


class Frame:
    """One cycle's percepts, grouped by type: type -> rows (neutral lists or tuples, as given,
    never changed). Rows of a type are validated when the type is read by column
    (``columns.read_cols``) or, for the rest, by ``check``; ``index`` is the executive's view."""

    __slots__ = ("groups", "checked", "shared", "patched", "cache", "_index")

    def __init__(self, groups: dict[str, list], checked: bool = False, shared: bool = False,
                 patched: dict | None = None):
        self.groups = groups
        self.checked = checked  # every row already validated (built from Percept objects)
        self.shared = shared  # the rows are SharedRows (shared_rows.py): identity = unchanged
        self.patched = patched  # last cycle's groups with new rows put in (shared_rows.Framer)
        self.cache: PerceptCache | None = None  # last cycle's Percepts, if read by column
        self._index: PerceptIndex | None = None

    @property
    def index(self) -> PerceptIndex:
        if self._index is None:
            self._index = PerceptIndex.of_groups(self.groups, self.cache)
        return self._index

    def check(self, types: Iterable[str]) -> None:
        """Validate the rows of ``types`` one by one (raises LangError naming the percept)."""
        for t in types:
            for row in self.groups[t]:
                check_row(row)


def frame_of(percepts: object) -> Frame:
    """Group ``percepts`` by type. Raises LangError naming a percept that is not a list or tuple
    ``[type, id, attr, value, ...]``; the values themselves are checked column by column later
    (``columns.read_cols``), or by ``Frame.check``."""
    if isinstance(percepts, PerceptIndex):
        return percepts.frame()
    if isinstance(percepts, Frame):
        return percepts
    items = percepts if isinstance(percepts, (list, tuple)) else list(percepts)
    if not _SEQS.issuperset(map(type, items)):
        items = [p.to_list() if isinstance(p, Percept) else p for p in items]
        if not _SEQS.issuperset(map(type, items)):
            for p in items:
                check_row(p)  # raises for the first non-list
    groups: dict = {}
    try:
        for t, run in groupby(items, _FIRST):
            rows = groups.get(t)
            if rows is None:
                groups[t] = list(run)
            else:
                rows.extend(run)
    except (IndexError, TypeError):  # an empty row, or an unhashable type
        for p in items:
            check_row(p)
        raise
    for t, rows in groups.items():
        if t.__class__ is not str:
            check_row(rows[0])  # raises: the type must be a symbol
    return Frame(groups)


class PerceptIndex:
    """Percepts of one cycle indexed by type, (type, id) and, on demand, (type, attr) -> value.
    Built lazily: from Percept objects, or from a Frame's rows, making Percepts only for the
    types and ids the executive asks about (most cycles it asks about few objects)."""

    __slots__ = ("_groups", "_percepts", "_by_type", "_by_id", "_attr", "_attrs")

    def __init__(self, percepts: Iterable[Percept] = ()):
        self._percepts: list[Percept] | None = list(percepts)
        self._groups: dict[str, list] | None = None
        self._by_type: Mapping[str, list[Percept]] | None = None
        self._by_id: Mapping[tuple, list[Percept]] | None = None
        self._attr: dict[tuple, dict] = {}
        self._attrs: dict[tuple, dict | None] = {}

    @classmethod
    def of_groups(cls, groups: dict[str, list], cache: PerceptCache | None = None) -> PerceptIndex:
        self = cls()
        self._percepts = None
        self._groups = groups
        # lazily at every size: a type the executive never asks about (at the demo's load,
        # most of them) costs no Percepts (docs/benchmarks.md, Engine)
        self._by_type = by_type = _ByType(groups, cache)
        self._by_id = _ById(groups, by_type)
        return self

    def frame(self) -> Frame:
        """The same percepts as a Frame (for inference)."""
        if self._groups is not None:
            return Frame(self._groups)
        groups: dict[str, list] = {}
        for p in self._percepts:
            groups.setdefault(p.type, []).append(p.to_list())
        return Frame(groups, checked=True)

    def rows(self) -> Iterator[list | tuple]:
        """Every percept as a neutral row, in no particular order (without making Percepts
        of rows that have none yet)."""
        if self._groups is not None:
            for rows in self._groups.values():
                yield from rows
        else:
            for p in self._percepts:
                yield p.to_list()

    @property
    def by_type(self) -> Mapping[str, list[Percept]]:
        """type -> its percepts."""
        if self._by_type is None:
            by_type: dict[str, list[Percept]] = {}
            for p in self._percepts:
                by_type.setdefault(p.type, []).append(p)
            self._by_type = by_type
        return self._by_type

    @property
    def by_id(self) -> Mapping[tuple, list[Percept]]:
        """(type, id) -> the percepts of that object (usually one)."""
        if self._by_id is None:
            by_id: dict[tuple, list[Percept]] = {}
            for p in self._percepts:
                by_id.setdefault((p.type, p.id), []).append(p)
            self._by_id = by_id
        return self._by_id

    def attr_index(self, type_: str, attr: str) -> dict:
        """value -> percepts of ``type_`` whose ``attr`` has that value."""
        key = (type_, attr)
        ix = self._attr.get(key)
        if ix is None:
            ix = {}
            for p in self.by_type.get(type_, ()):
                v = p._map.get(attr, MISSING)
                if v is not MISSING:
                    ix.setdefault(v, []).append(p)
            self._attr[key] = ix
        return ix

    def attrs_index(self, type_: str, attrs: tuple[str, ...], with_id: bool = False
                    ) -> dict | None:
        """(value, ...) -> percepts of ``type_`` with those values of ``attrs`` (each list in
        the order of ``by_type``; ``with_id``: the key's first value is the id); None when some
        value cannot be a key (unhashable)."""
        key = (type_, attrs, with_id)
        if key in self._attrs:
            return self._attrs[key]
        ix: dict | None = {}
        for p in self.by_type.get(type_, ()):
            m = p._map
            vs = tuple([m.get(a, MISSING) for a in attrs])
            if with_id:
                vs = (p.id, *vs)
            if MISSING not in vs:
                try:
                    ix.setdefault(vs, []).append(p)
                except TypeError:
                    ix = None
                    break
        self._attrs[key] = ix
        return ix


class _ByType(Mapping):
    """type -> Percepts, each type's made on first use from its rows."""

    def __init__(self, groups: dict[str, list], cache: PerceptCache | None):
        self.groups = groups
        self.cache = cache
        self.made: dict[str, list[Percept]] = {}

    def __getitem__(self, t: str) -> list[Percept]:
        got = self.made.get(t)
        if got is None:
            rows = self.groups[t]
            got = self.cache.percepts(t, rows) if self.cache is not None else \
                list(map(Percept.of_row, rows))
            self.made[t] = got
        return got

    def get(self, t: str, default: object = None) -> object:
        got = self.made.get(t)
        if got is not None:
            return got
        return self[t] if t in self.groups else default

    def __iter__(self) -> Iterator[str]:
        return iter(self.groups)

    def __len__(self) -> int:
        return len(self.groups)


class _ById(Mapping):
    """(type, id) -> Percepts, made on first use; a type's ids are indexed on first use."""

    def __init__(self, groups: dict[str, list], by_type: _ByType):
        self.groups = groups
        self.by_type = by_type
        self.rows: dict[str, dict] = {}  # type -> id -> row position, or list of positions
        self.made: dict[tuple, list[Percept]] = {}

    def _rows(self, t: str) -> dict:
        ix = self.rows.get(t)
        if ix is None:
            rows = self.groups.get(t, ())
            ix = dict(zip(map(_SECOND, rows), count()))
            if len(ix) != len(rows):  # an id given twice
                ix = {}
                for i, r in enumerate(rows):
                    ix.setdefault(r[1], []).append(i)
            self.rows[t] = ix
        return ix

    def __getitem__(self, key: tuple) -> list[Percept]:
        got = self.made.get(key)
        if got is None:
            if not isinstance(key, tuple) or len(key) != 2:
                raise KeyError(key)
            t = key[0]
            at = self._rows(t)[key[1]]
            made = self.by_type.made.get(t)
            if made is not None:
                got = [made[at]] if isinstance(at, int) else [made[i] for i in at]
            else:
                rows = self.groups[t]
                got = [Percept.of_row(rows[at])] if isinstance(at, int) else \
                    [Percept.of_row(rows[i]) for i in at]
            self.made[key] = got
        return got

    def get(self, key: tuple, default: object = None) -> object:
        got = self.made.get(key)
        if got is not None:
            return got
        try:
            return self[key]
        except KeyError:
            return default

    def __iter__(self) -> Iterator[tuple]:
        return ((t, i) for t in self.groups for i in self._rows(t))

    def __len__(self) -> int:
        return sum(len(self._rows(t)) for t in self.groups)


class PerceptCache:
    """Each type's Percepts of the last cycle they were asked for, with the columns they were
    made from (``cols``: this cycle's columns per type, kept by inference's tracker): the next
    cycle makes Percepts only for the rows that changed (strictly) since."""

    def __init__(self, cols: dict):
        self.cols = cols
        self.last: dict[str, tuple] = {}

    def percepts(self, t: str, rows: list) -> list[Percept]:
        new = self.cols.get(t)
        prev = self.last.get(t)
        if new is None:
            self.last.pop(t, None)
            return list(map(Percept.of_row, rows))
        if prev is not None and prev[0] is new:
            return prev[1]
        if prev is None or prev[0].names != new.names or prev[0].ids != new.ids:
            out = list(map(Percept.of_row, rows))
        else:
            old, out = prev[0], list(prev[1])
            moved = set()
            for a in (ID, *new.names):
                moved.update(changed(old.vals[a], new.vals[a], old.types[a], new.types[a],
                                     float in new.kinds[a]))
            for i in moved:
                out[i] = Percept.of_row(rows[i])
        self.last[t] = (new, out)
        return out


_SECOND = itemgetter(1)
