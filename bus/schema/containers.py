"""Container specs: a Record, Tagged, ListOf, MapOf or TupleOf checks its items with their own
specs and adds the item's key or index to the path of an item's error (bus/schema/specs.py
says how a spec checks)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from bus.schema.brief import brief
from bus.schema.specs import FieldError, Spec, Str

__all__ = ["AnyOf", "ListOf", "MapOf", "Record", "Tagged", "TupleOf"]

_STR_ONLY = frozenset({str})


class ListOf(Spec):
    """An array of at most ``max_len`` items (at least ``min_len``), each fitting ``item``."""

    def __init__(self, item: Spec, max_len: int = 10_000, min_len: int = 0,
                 what: str = "") -> None:
        self.item, self.max_len, self.min_len = item, max_len, min_len
        self.expected = what or "an array"

    def refuse(self, value: Any) -> FieldError:
        if type(value) is list:
            return FieldError(f"expected {self.expected} of {self.min_len} to {self.max_len} "
                              f"items, got {len(value)}: {brief(value)}")
        return super().refuse(value)

    def check(self, value: Any) -> Any:
        if type(value) is not list or not self.min_len <= len(value) <= self.max_len:
            raise self.refuse(value)
        check = self.item.check
        for i, x in enumerate(value):
            try:
                check(x)
            except FieldError as exc:
                raise exc.within(i) from None
        return value


class TupleOf(Spec):
    """An array of exactly one item per spec: ``[width, height]``."""

    def __init__(self, *items: Spec, what: str = "") -> None:
        self.items = items
        self._checks = tuple(spec.check for spec in items)
        self.expected = what or f"an array of {len(items)} items"

    def check(self, value: Any) -> Any:
        if type(value) is not list or len(value) != len(self.items):
            raise self.refuse(value)
        try:
            for check, x in zip(self._checks, value, strict=True):
                check(x)
        except FieldError:
            for i, (check, x) in enumerate(zip(self._checks, value, strict=True)):
                try:
                    check(x)
                except FieldError as exc:
                    raise exc.within(i) from None
        return value


class MapOf(Spec):
    """A map of at most ``max_len`` entries whose keys fit ``key`` and values ``value``."""

    def __init__(self, value: Spec, key: Spec | None = None, max_len: int = 10_000,
                 what: str = "") -> None:
        self.key, self.value, self.max_len = key or Str(), value, max_len
        self.expected = what or "a map"

    def refuse(self, value: Any) -> FieldError:
        if type(value) is dict:
            return FieldError(f"expected {self.expected} of at most {self.max_len} entries, "
                              f"got {len(value)}")
        return super().refuse(value)

    def check(self, value: Any) -> Any:
        if type(value) is not dict or len(value) > self.max_len:
            raise self.refuse(value)
        key = self.key
        if type(key) is Str and key.pattern is None and not key.min_len:   # names: in C
            if not (_STR_ONLY.issuperset(map(type, value))
                    and max(map(len, value), default=0) <= key.max_len):
                bad = next(k for k in value if type(k) is not str or len(k) > key.max_len)
                raise FieldError(f"key {key.refuse(bad).problem}")
        else:
            for k in value:
                try:
                    key.check(k)
                except FieldError as exc:
                    raise FieldError(f"key {exc.problem}") from None
        check_value = self.value.check
        for k, v in value.items():
            try:
                check_value(v)
            except FieldError as exc:
                raise exc.within(k) from None
        return value


class Record(Spec):
    """A map with named fields: every ``required`` one, any ``optional`` one, and (unless
    ``open``) no other, so a misspelt or invented field is refused by name, as a scenario
    file's unknown key is."""

    def __init__(self, required: Mapping[str, Spec], optional: Mapping[str, Spec] | None = None,
                 open: bool = False, what: str = "a map") -> None:
        self.required, self.optional = dict(required), dict(optional or {})
        self.fields = {**self.required, **self.optional}
        self._required = frozenset(self.required)
        self._checks = {name: spec.check for name, spec in self.fields.items()}
        self._all, self._pairs = self.fields.keys(), tuple(self._checks.items())
        self.open = open
        self.expected = what

    def check(self, value: Any) -> Any:
        if type(value) is not dict:
            raise self.refuse(value)
        if value.keys() == self._all:   # every field there (the usual case): no lookups
            try:
                for name, check in self._pairs:
                    check(value[name])
            except FieldError as exc:
                raise exc.within(name) from None
            return value
        if not self._required <= value.keys():
            name = next(n for n in self.required if n not in value)
            raise FieldError(f"missing; expected {self.required[name].expected}", (name,))
        checks = self._checks
        for name, v in value.items():
            check = checks.get(name) if type(name) is str else None
            if check is None:
                if self.open:
                    continue
                raise FieldError(f"unknown field {brief(name)}; known: "
                                 f"{', '.join(self.fields) or 'none'}")
            try:
                check(v)
            except FieldError as exc:
                raise exc.within(name) from None
        return value


class AnyOf(Spec):
    """The first of a few specs that fits (an operation record, or the empty map)."""

    def __init__(self, *specs: Spec, what: str = "") -> None:
        self.specs = specs
        self.expected = what or " or ".join(s.expected for s in specs)

    def check(self, value: Any) -> Any:
        last: FieldError | None = None
        for spec in self.specs:
            try:
                return spec.check(value)
            except FieldError as exc:
                last = exc
        raise last if last is not None else self.refuse(value)


class Tagged(Spec):
    """A map whose ``tag`` field (a string) says which Record the rest must fit: the events
    of a world, ``{"kind": "block", "segment": "S17"}``. The tag field is part of each
    record; an unknown tag is refused listing the known ones."""

    def __init__(self, records: Mapping[str, Record], tag: str = "kind",
                 what: str = "") -> None:
        self.tag = tag
        self.records = {k: Record({tag: Str(), **r.required}, r.optional, r.open, r.expected)
                        for k, r in records.items()}
        self.kinds = tuple(self.records)
        self.expected = what or f'a map with a "{tag}"'

    def check(self, value: Any) -> Any:
        if type(value) is not dict:
            raise self.refuse(value)
        kind = value.get(self.tag)
        record = self.records.get(kind) if type(kind) is str else None
        if record is None:
            if self.tag not in value:
                raise FieldError(f"missing; expected one of {', '.join(self.kinds)}",
                                 (self.tag,))
            raise FieldError(f"unknown {self.tag} {brief(kind)}; known: {' '.join(self.kinds)}")
        return record.check(value)
