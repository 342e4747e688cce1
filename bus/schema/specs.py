"""Field specs: what one value of a message must be, and its check; the scalar specs here, the
containers in bus/schema/containers.py.

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
from collections.abc import Sequence
from typing import Any

from bus.schema.brief import brief

__all__ = ["Atom", "Bool", "FieldError", "Int", "Num", "OneOf", "Spec", "Str"]

INT64 = (-(2**63), 2**63 - 1)
"""Signed 64-bit integers (what the language and the records keep to)."""
WIRE_INT = (-(2**63), 2**64 - 1)
"""The integers msgpack carries (signed and unsigned 64-bit): what Int allows by default."""
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_-]{0,63}")  # a key shown bare in a path


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
