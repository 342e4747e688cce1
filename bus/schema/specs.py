"""Field specs: what one value of a message must be, and its check.

A spec is a small frozen object with ``check(value) -> value``: the value itself when it fits
(never converted, so what a process goes on with is byte for byte what it was sent), else
FieldError naming the field's path within the message and what was expected. Containers
(Record, Tagged, ListOf, MapOf, TupleOf) check their items with their own specs and add the
item's key or index to the path of an item's error, so a message's schema reads as the
message does:

    PACKAGE = Record({"id": ID, "address": Int(-10**6, 10**6), "street": Str(),
                      "owner": ID})
    PACKAGE.check({"id": "P9", "address": 3, "street": "B", "owner": []})
    -> FieldError("owner: expected a name (letters, digits, '_' or '-', ...), got []")
"""

from __future__ import annotations

import math
import re
import sys
from collections.abc import Mapping, Sequence
from typing import Any

from bus.schema.brief import brief

__all__ = ["AnyOf", "Atom", "Bool", "FieldError", "Int", "ListOf", "MapOf", "Num", "OneOf",
           "Record", "Spec", "Str", "Tagged", "TupleOf"]

INT64 = (-(2**63), 2**63 - 1)
WIRE_INT = (-(2**63), 2**64 - 1)
"""The integers msgpack carries (signed and unsigned 64-bit): what Int allows by default."""
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_-]{0,63}")  # a key shown bare in a path
_STR_ONLY = frozenset({str})
"""Signed 64-bit integers (what the language and the records keep to)."""


class FieldError(ValueError):
    """A value that does not fit its spec. ``path``: the field within the message, as keys and
    [indexes] ("owner", "cars[2].x", "" for the value itself); ``problem``: what is wrong and
    what would be right."""

    def __init__(self, problem: str, path: tuple[str | int, ...] = ()) -> None:
        self.problem, self.path = problem, path
        where = self.where
        super().__init__(f"{where}: {problem}" if where else problem)

    @property
    def where(self) -> str:
        """The path as text: ``cars[2].x``."""
        out = ""
        for part in self.path:
            if isinstance(part, int) or not _NAME.fullmatch(part):
                out += f"[{brief(part, 30)}]" if not isinstance(part, int) else f"[{part}]"
            else:
                out += f".{part}" if out else part
        return out

    def within(self, part: str | int) -> FieldError:
        """The same error, seen from the container holding the value at ``part``."""
        return FieldError(self.problem, (part, *self.path))


class Spec:
    """What a value must be: ``expected`` says it in words ("a number in [0, 10]")."""

    expected = "a value"

    def check(self, value: Any) -> Any:
        """``value`` when it fits; else raises FieldError."""
        raise NotImplementedError

    def refuse(self, value: Any) -> FieldError:
        """The error for a ``value`` that does not fit."""
        return FieldError(f"expected {self.expected}, got {brief(value)}")


def _bounds(lo: float | None, hi: float | None) -> str:
    def show(v: float) -> str:
        return f"{v:g}" if type(v) is float else str(v)

    if lo is not None and hi is not None:
        return f" in [{show(lo)}, {show(hi)}]"
    if lo is not None:
        return f" >= {show(lo)}"
    return f" <= {show(hi)}" if hi is not None else ""


class Int(Spec):
    """An integer (never a bool) within [lo, hi] (default: what msgpack carries)."""

    def __init__(self, lo: int | None = WIRE_INT[0], hi: int | None = WIRE_INT[1],
                 what: str = "an integer") -> None:
        self.lo, self.hi = lo, hi
        self._lo = -math.inf if lo is None else lo
        self._hi = math.inf if hi is None else hi
        self.expected = what + _bounds(lo, hi) if (lo, hi) != WIRE_INT else what

    def check(self, value: Any) -> Any:
        if type(value) is not int or not self._lo <= value <= self._hi:
            raise self.refuse(value)
        return value


class Num(Spec):
    """A finite number, int or float (never a bool, NaN or an infinity), within [lo, hi];
    ``as_float``: given back as a float (else as it came)."""

    def __init__(self, lo: float | None = None, hi: float | None = None,
                 what: str = "a number", as_float: bool = False) -> None:
        self.lo, self.hi, self.as_float = lo, hi, as_float
        # NaN fails every comparison, and an infinity is beyond the largest float
        self._lo = -sys.float_info.max if lo is None else lo
        self._hi = sys.float_info.max if hi is None else hi
        self.expected = what + _bounds(lo, hi) if (lo, hi) != (None, None) else \
            f"a finite {what.removeprefix('a ')}"

    def check(self, value: Any) -> Any:
        kind = type(value)
        if (kind is not float and kind is not int) or not self._lo <= value <= self._hi:
            raise self.refuse(value)
        return float(value) if self.as_float else value


class Str(Spec):
    """A string of at most ``max_len`` characters (and at least ``min_len``), matching
    ``pattern`` if given."""

    def __init__(self, max_len: int = 256, what: str = "a string", pattern: str = "",
                 min_len: int = 0) -> None:
        self.max_len, self.min_len = max_len, min_len
        self.pattern = re.compile(pattern) if pattern else None
        self.expected = what

    def check(self, value: Any) -> Any:
        if type(value) is not str or not self.min_len <= len(value) <= self.max_len or \
                (self.pattern is not None and not self.pattern.fullmatch(value)):
            raise self.refuse(value)
        return value

    def refuse(self, value: Any) -> FieldError:
        if type(value) is str and len(value) > self.max_len:
            return FieldError(f"expected {self.expected} of at most {self.max_len} characters, "
                              f"got {brief(value)}")
        if type(value) is str and len(value) < self.min_len:
            return FieldError(f"expected {self.expected} (not empty), got {brief(value)}")
        return super().refuse(value)


class Bool(Spec):
    expected = "true or false"

    def check(self, value: Any) -> Any:
        if type(value) is not bool:
            raise self.refuse(value)
        return value


class Atom(Spec):
    """A neutral-form atom: a string or a finite number (never a bool or null)."""

    expected = "a string or a finite number"

    def check(self, value: Any) -> Any:
        kind = type(value)
        if kind is str or kind is int or (kind is float and math.isfinite(value)):
            return value
        raise self.refuse(value)


class OneOf(Spec):
    """One of a few strings (or other atoms)."""

    def __init__(self, choices: Sequence[Any], what: str = "") -> None:
        self.choices = tuple(choices)
        self._set = frozenset((type(c), c) for c in self.choices)
        listed = ", ".join(map(repr, self.choices))
        self.expected = f"{what}, one of {listed}" if what else f"one of {listed}"

    def check(self, value: Any) -> Any:
        if type(value) not in (str, int, float) or (type(value), value) not in self._set:
            raise self.refuse(value)
        return value


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
