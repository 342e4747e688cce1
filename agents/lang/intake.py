"""Percepts entering the engine: neutral lists (as msgpack decodes them) or Percept objects,
checked once per message in a few C-level passes and grouped by type, without building a
Percept per object. Percept objects are built only when the executive asks for them
(``PerceptIndex``); inference reads the grouped rows by column (``columns.py``)."""

from __future__ import annotations

from collections.abc import Iterable
from itertools import groupby
from operator import itemgetter

from .terms import Percept, check_row

MISSING = object()
_SEQS = frozenset({list, tuple})
_FIRST = itemgetter(0)


class Frame:
    """One cycle's percepts, grouped by type: type -> rows (neutral lists or tuples, as given,
    never changed). Rows of a type are validated when the type is read by column
    (``columns.read``) or, for the rest, by ``check``; ``index`` is the executive's view."""

    __slots__ = ("groups", "checked", "_index")

    def __init__(self, groups: dict[str, list], checked: bool = False):
        self.groups = groups
        self.checked = checked  # every row already validated (built from Percept objects)
        self._index: PerceptIndex | None = None

    @property
    def index(self) -> PerceptIndex:
        if self._index is None:
            self._index = PerceptIndex.of_groups(self.groups)
        return self._index

    def check(self, types: Iterable[str]) -> None:
        """Validate the rows of ``types`` one by one (raises LangError naming the percept)."""
        for t in types:
            for row in self.groups[t]:
                check_row(row)


def frame_of(percepts: object) -> Frame:
    """Group ``percepts`` by type. Raises LangError naming a percept that is not a list or tuple
    ``[type, id, attr, value, ...]``; the values themselves are checked column by column later
    (``columns.read``), or by ``Frame.check``."""
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
    Built lazily: from Percept objects, or from a Frame's rows, making a Percept per row only
    when the executive first asks (most cycles it asks about few types)."""

    __slots__ = ("_groups", "_percepts", "_by_type", "_by_id", "_attr")

    def __init__(self, percepts: Iterable[Percept] = ()):
        self._percepts: list[Percept] | None = list(percepts)
        self._groups: dict[str, list] | None = None
        self._by_type: dict[str, list[Percept]] | None = None
        self._by_id: dict[tuple, list[Percept]] | None = None
        self._attr: dict[tuple, dict] = {}

    @classmethod
    def of_groups(cls, groups: dict[str, list]) -> PerceptIndex:
        self = cls()
        self._percepts = None
        self._groups = groups
        return self

    def frame(self) -> Frame:
        """The same percepts as a Frame (for inference)."""
        if self._groups is not None:
            return Frame(self._groups)
        groups: dict[str, list] = {}
        for p in self._percepts:
            groups.setdefault(p.type, []).append(p.to_list())
        return Frame(groups, checked=True)

    @property
    def by_type(self) -> dict[str, list[Percept]]:
        if self._by_type is None:
            if self._groups is not None:
                of_row = Percept.of_row
                self._by_type = {t: list(map(of_row, rows)) for t, rows in self._groups.items()}
            else:
                self._by_type = {}
                for p in self._percepts:
                    self._by_type.setdefault(p.type, []).append(p)
        return self._by_type

    @property
    def by_id(self) -> dict[tuple, list[Percept]]:
        if self._by_id is None:
            by_id: dict[tuple, list[Percept]] = {}
            for t, ps in self.by_type.items():
                for p in ps:
                    k = (t, p.id)
                    same = by_id.get(k)
                    if same is None:
                        by_id[k] = [p]
                    else:
                        same.append(p)
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
