"""Indexed stores of percepts (by type, id, attribute value) and of facts (by bound argument
positions), shared by inference and the executive. Indexes are built lazily and cached."""

from __future__ import annotations

import marshal
from collections.abc import Iterable

from .terms import Belief, Percept

MISSING = object()


class TypeSig:
    """The percepts of one type in one cycle, comparable with another cycle's (``same``).

    Two cycles' percepts are the same when they are equal as sets (order and duplicates do not
    matter to inference) *and* each value has the same type and bits: 3 == 3.0 and 0.0 == -0.0
    in Python, but a belief taking the value prints differently. The cheap set comparison comes
    first (it settles most changed cycles); only equal sets are compared strictly, encoding each
    percept with ``marshal`` format 2 (exact str, int, float, bool only; floats in binary; no
    shared references, so the encoding does not depend on how strings were built)."""

    __slots__ = ("tuples", "lax", "_strict")

    def __init__(self, percepts: Iterable[Percept]):
        self.tuples = [(p.type, p.id, p.attrs) for p in percepts]
        try:
            self.lax: frozenset | None = frozenset(self.tuples)
        except TypeError:  # an unhashable value: never the same
            self.lax = None
        self._strict: frozenset | None | bool = False  # False: not computed yet

    def strict(self) -> frozenset | None:
        """The exact encodings of the percepts (cached), or None if one cannot be encoded."""
        if self._strict is False:
            try:
                self._strict = frozenset([marshal.dumps(t, 2) for t in self.tuples])
            except ValueError:
                self._strict = None
        return self._strict  # type: ignore[return-value]

    def same(self, old: TypeSig) -> bool:
        """True when these percepts are exactly ``old``'s, up to order and duplicates."""
        if self is old:
            return True
        if self.lax is None or self.lax != old.lax:
            return False
        mine = self.strict()
        return mine is not None and mine == old.strict()


class PerceptIndex:
    """Percepts of one cycle indexed by type, (type, id) and, on demand, (type, attr) -> value."""

    __slots__ = ("by_type", "by_id", "_attr", "_sig")

    def __init__(self, percepts: Iterable[Percept]):
        self.by_type: dict[str, list[Percept]] = {}
        self.by_id: dict[tuple, list[Percept]] = {}
        self._attr: dict[tuple, dict] = {}
        self._sig: dict[str, TypeSig] = {}
        for p in percepts:
            self.by_type.setdefault(p.type, []).append(p)
            self.by_id.setdefault((p.type, p.id), []).append(p)

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

    def signature(self, type_: str) -> TypeSig:
        """The percepts of ``type_`` in a canonical, order-independent form (cached)."""
        sig = self._sig.get(type_)
        if sig is None:
            sig = self._sig[type_] = TypeSig(self.by_type.get(type_, ()))
        return sig


class FactStore:
    """Facts as pred -> set of argument tuples, with cached indexes on bound positions."""

    __slots__ = ("facts", "_ix")

    def __init__(self, facts: dict[str, set] | None = None):
        self.facts: dict[str, set] = facts if facts is not None else {}
        self._ix: dict[tuple, dict] = {}

    def get(self, pred: str) -> set:
        """All argument tuples of ``pred`` (empty set if none)."""
        return self.facts.get(pred) or _EMPTY

    def add(self, pred: str, tuples: Iterable[tuple]) -> None:
        """Add facts of ``pred`` and drop its cached indexes."""
        self.facts.setdefault(pred, set()).update(tuples)
        for key in [k for k in self._ix if k[0] == pred]:
            del self._ix[key]

    def index(self, pred: str, positions: tuple[int, ...]) -> dict:
        """key tuple (values at ``positions``) -> list of argument tuples."""
        key = (pred, positions)
        ix = self._ix.get(key)
        if ix is None:
            ix = {}
            for t in self.facts.get(pred, ()):
                ix.setdefault(tuple(t[i] for i in positions), []).append(t)
            self._ix[key] = ix
        return ix

    def adopt(self, old: FactStore, preds: Iterable[str]) -> None:
        """Take ``old``'s fact sets and cached indexes for ``preds`` (no copy): used when a
        stratum's result is reused from the previous cycle. Sound because inference never
        changes a pred's set after its stratum is done, so both stores read the same facts."""
        wanted = {p for p in preds if p in old.facts}
        for p in wanted:
            self.facts[p] = old.facts[p]
        for key, ix in old._ix.items():
            if key[0] in wanted:
                self._ix[key] = ix

    def beliefs(self) -> frozenset[Belief]:
        return frozenset(Belief(p, t) for p, ts in self.facts.items() for t in ts)


_EMPTY: set = set()


class BeliefSet(frozenset):
    """frozenset of Belief that also carries the FactStore it came from (saves re-indexing)."""

    store: FactStore

    def __new__(cls, store: FactStore):
        new = tuple.__new__
        self = super().__new__(cls, (new(Belief, (p, t)) for p, ts in store.facts.items()
                                     for t in ts))
        self.store = store
        return self


def store_of(beliefs: Iterable[Belief]) -> FactStore:
    """The FactStore behind ``beliefs`` (built if they are a plain collection)."""
    store = getattr(beliefs, "store", None)
    if isinstance(store, FactStore):
        return store
    facts: dict[str, set] = {}
    for b in beliefs:
        if not isinstance(b, Belief):
            b = Belief.from_list(b)
        facts.setdefault(b.pred, set()).add(tuple(b.args))
    return FactStore(facts)
