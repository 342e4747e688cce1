"""Relation stores shared by inference and the executive: named sets of argument tuples with
indexes on bound positions that are built on first use and then kept up to date as tuples are
inserted and deleted (never rebuilt). ``OldView`` reads a store as it was before this pass's
changes, which incremental inference needs (docs/language.md, Performance)."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from itertools import chain
from operator import itemgetter

from .intake import MISSING, PerceptIndex
from .terms import Belief

__all__ = ["MISSING", "BeliefSet", "Delta", "FactStore", "OldView", "PerceptIndex", "store_of"]

_EMPTY: frozenset = frozenset()
_new_tuple = tuple.__new__


def key_getter(positions: tuple[int, ...]):
    """Function giving a tuple's index key: the tuple of its values at ``positions``."""
    if len(positions) == 1:
        p = positions[0]
        return lambda t: (t[p],)
    return itemgetter(*positions)


class FactStore:
    """Relations as name -> set of argument tuples, with maintained indexes on bound positions.

    Concept facts are keyed by predicate (str); the percept relations that inference builds are
    keyed by (type, attrs). ``version`` counts the runs that changed the store. Its facts change
    only through ``insert``, ``delete``, ``replace`` and ``add``, which keep what is derived from
    them (the indexes, ``lines``) what it would be made afresh."""

    __slots__ = ("facts", "_ix", "_by_rel", "_text", "version")

    def __init__(self, facts: dict | None = None):
        self.facts: dict = facts if facts is not None else {}
        self._ix: dict[tuple, dict] = {}
        self._by_rel: dict[object, list] = {}  # rel -> [(key function, index), ...]
        self._text: dict[object, tuple[str, ...]] = {}  # rel -> ``lines(rel)``, until it changes
        self.version = 0

    def get(self, rel: object) -> set | frozenset:
        """All argument tuples of ``rel`` (an empty set if none)."""
        return self.facts.get(rel) or _EMPTY

    def index(self, rel: object, positions: tuple[int, ...]) -> dict:
        """key tuple (values at ``positions``) -> set of argument tuples; kept up to date."""
        ix = self._ix.get((rel, positions))
        if ix is None:
            ix = self._ix[(rel, positions)] = {}
            key = key_getter(positions)
            _fill(ix, key, self.facts.get(rel, ()))
            self._by_rel.setdefault(rel, []).append((key, ix))
        return ix

    def lines(self, rel: object) -> tuple[str, ...]:
        """The ``repr`` of every tuple of ``rel``, sorted (the text the loop watch digests);
        kept, as the indexes are, until ``rel`` changes, so that the digest of a cycle pays
        only for the relations that changed since the last one."""
        got = self._text.get(rel)
        if got is None:
            got = self._text[rel] = tuple(sorted(map(repr, self.facts.get(rel, ()))))
        return got

    def has_index(self, rel: object, positions: tuple[int, ...]) -> bool:
        return (rel, positions) in self._ix

    def insert(self, rel: object, tuples: list) -> None:
        """Add ``tuples``, none of them present yet, keeping the indexes up to date."""
        if not tuples:
            return
        self._text.pop(rel, None)
        s = self.facts.get(rel)
        if s is None:
            s = self.facts[rel] = set()
        s.update(tuples)
        for key, ix in self._by_rel.get(rel, ()):
            _fill(ix, key, tuples)

    def delete(self, rel: object, tuples: list) -> None:
        """Remove ``tuples``, all of them present, keeping the indexes up to date."""
        if not tuples:
            return
        self._text.pop(rel, None)
        s = self.facts[rel]
        s.difference_update(tuples)
        for key, ix in self._by_rel.get(rel, ()):
            for t in tuples:
                k = key(t)
                bucket = ix[k]
                bucket.discard(t)
                if not bucket:
                    del ix[k]

    def replace(self, rel: object, tuples: Iterable[tuple]) -> None:
        """Make ``rel`` hold exactly ``tuples`` (its indexes are dropped and built again on use)."""
        self.facts[rel] = set(tuples)
        self._text.pop(rel, None)
        for _key, ix in self._by_rel.pop(rel, ()):
            ix.clear()
        for k in [k for k in self._ix if k[0] == rel]:
            del self._ix[k]

    def add(self, rel: object, tuples: Iterable[tuple]) -> None:
        """Add facts of ``rel`` (those already present are skipped)."""
        have = self.get(rel)
        self.insert(rel, [t for t in set(tuples) if t not in have])

    def beliefs(self) -> frozenset[Belief]:
        return frozenset(_new_tuple(Belief, (p, t)) for p, ts in self.facts.items() for t in ts)


def _fill(ix: dict, key, tuples) -> None:
    """Add ``tuples`` to index ``ix`` (key -> set of tuples)."""
    for t in tuples:
        k = key(t)
        bucket = ix.get(k)
        if bucket is None:
            ix[k] = {t}
        else:
            bucket.add(t)


class Delta:
    """The set-level change of one relation in one pass: tuples deleted and inserted."""

    __slots__ = ("dels", "ins", "_dset", "_iset", "_dix")

    def __init__(self, dels: list, ins: list):
        self.dels = dels
        self.ins = ins
        self._dset: set | None = None
        self._iset: set | None = None
        self._dix: dict = {}

    def __bool__(self) -> bool:
        return bool(self.dels or self.ins)

    def __repr__(self) -> str:
        return f"Delta(dels={self.dels!r}, ins={self.ins!r})"

    @property
    def dset(self) -> set:
        if self._dset is None:
            self._dset = set(self.dels)
        return self._dset

    @property
    def iset(self) -> set:
        if self._iset is None:
            self._iset = set(self.ins)
        return self._iset

    def dels_index(self, positions: tuple[int, ...]) -> dict:
        ix = self._dix.get(positions)
        if ix is None:
            ix = self._dix[positions] = {}
            key = key_getter(positions)
            for t in self.dels:
                ix.setdefault(key(t), []).append(t)
        return ix


class _OldSet:
    """A relation as it was before a Delta: current tuples minus inserted plus deleted."""

    __slots__ = ("cur", "d")

    def __init__(self, cur: set, d: Delta):
        self.cur = cur
        self.d = d

    def __contains__(self, t: tuple) -> bool:
        return (t in self.cur and t not in self.d.iset) or t in self.d.dset

    def __iter__(self) -> Iterator[tuple]:
        iset = self.d.iset
        return chain([t for t in self.cur if t not in iset], self.d.dels)

    def __len__(self) -> int:
        return len(self.cur) - len(self.d.ins) + len(self.d.dels)

    def __bool__(self) -> bool:
        return len(self) > 0


class _OldIndex:
    """An index as it was before a Delta (``get`` only)."""

    __slots__ = ("cur", "d", "positions")

    def __init__(self, cur: dict, d: Delta, positions: tuple[int, ...]):
        self.cur = cur
        self.d = d
        self.positions = positions

    def get(self, key: tuple, default: object = ()) -> list:
        bucket = self.cur.get(key)
        iset = self.d.iset
        out = [t for t in bucket if t not in iset] if bucket else []
        old = self.d.dels_index(self.positions).get(key)
        if old:
            out += old
        return out


class OldView:
    """Read-only view of a store as it was before ``changes`` (rel -> Delta) were applied."""

    __slots__ = ("store", "changes")

    def __init__(self, store: FactStore, changes: dict):
        self.store = store
        self.changes = changes

    def get(self, rel: object):
        d = self.changes.get(rel)
        cur = self.store.get(rel)
        return cur if d is None else _OldSet(cur, d)

    def index(self, rel: object, positions: tuple[int, ...]):
        d = self.changes.get(rel)
        cur = self.store.index(rel, positions)
        return cur if d is None else _OldIndex(cur, d, positions)


class BeliefSet(frozenset):
    """frozenset of Belief that also gives the FactStore it came from (saves re-indexing).

    Inference keeps one live store and changes it in place each cycle, so ``store`` is that live
    store while it still holds these beliefs, and otherwise a store built from them (once)."""

    def __new__(cls, beliefs: Iterable[Belief] | FactStore, live: FactStore | None = None):
        if isinstance(beliefs, FactStore):
            live, beliefs = beliefs, beliefs.beliefs()
        self = super().__new__(cls, beliefs)
        self._live = live
        self._version = live.version if live is not None else -1
        self._own = None
        return self

    @property
    def store(self) -> FactStore:
        live = self._live
        if live is not None and live.version == self._version:
            return live
        if self._own is None:
            self._own = _store_from(self)
        return self._own


def _store_from(beliefs: Iterable) -> FactStore:
    facts: dict[str, set] = {}
    for b in beliefs:
        if not isinstance(b, Belief):
            b = Belief.from_list(b)
        facts.setdefault(b.pred, set()).add(tuple(b.args))
    return FactStore(facts)


def store_of(beliefs: Iterable[Belief]) -> FactStore:
    """The FactStore behind ``beliefs`` (built if they are a plain collection)."""
    if isinstance(beliefs, BeliefSet):
        return beliefs.store
    store = getattr(beliefs, "store", None)
    if isinstance(store, FactStore):
        return store
    return _store_from(beliefs)
