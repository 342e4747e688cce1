"""Plain data: the values that may travel in a field whose inside another package reads (an
agent's memory, a world snapshot, an intention), checked only for what every reader and
writer of it relies on: null, booleans, integers of at most 64 bits, finite floats, strings,
arrays and maps with string keys, nested at most ``max_depth`` levels. So such a value can
always be encoded again (msgpack stops at 512 levels), written to JSON (no NaN, no bytes) and
shown in a message."""

from __future__ import annotations

from collections import deque
from math import isfinite
from typing import Any

from bus.schema.specs import FieldError, Spec

_ATOMS = frozenset({str, int, float, bool, type(None)})
_CONTAINERS = (dict, list)
_CONTAINER_SET = frozenset(_CONTAINERS)
_STR_ONLY = frozenset({str})
_LO, _HI = -(2**63), 2**64 - 1   # the integers msgpack carries


class Plain(Spec):
    """Plain data (see the module) nested at most ``max_depth`` levels; ``top`` the type the
    value itself must have (dict: a map), if any."""

    def __init__(self, max_depth: int = 32, top: type | None = dict,
                 what: str = "") -> None:
        self.max_depth, self.top = max_depth, top
        self.expected = what or ("a map of plain data" if top is dict else "plain data")

    def check(self, value: Any) -> Any:
        if self.top is not None and type(value) is not self.top:
            raise self.refuse(value)
        if type(value) not in _CONTAINER_SET:
            return self._atom_ok(value)
        if not _fits(value, self.max_depth):
            raise _where(value, self.max_depth)
        return value

    def _atom_ok(self, value: Any) -> Any:
        if type(value) not in _ATOMS or (type(value) is float and not isfinite(value)) or \
                (type(value) is int and not _LO <= value <= _HI) or \
                (type(value) is str and not _utf8([value])):
            raise self.refuse(value)
        return value


def _utf8(items: list) -> bool:
    """Every string among ``items`` can be written as UTF-8 (no lone surrogate)."""
    try:
        for x in items:
            if type(x) is str and not x.isascii():
                x.encode("utf-8")
    except UnicodeEncodeError:
        return False
    return True


def _fits(v: Any, left: int) -> bool:
    """Whether the map or array ``v`` and everything in it is plain data nested at most
    ``left`` levels: one pass over each container's items, the common atoms first (the hot
    path: a memory, an intention, every cycle)."""
    if left <= 0:
        return False
    if type(v) is dict:
        if not (_STR_ONLY.issuperset(map(type, v)) and (all(map(str.isascii, v))
                                                         or _utf8(list(v)))):
            return False
        items: Any = v.values()
    else:
        items = v
    for x in items:
        t = type(x)
        if t is str:
            if not x.isascii() and not _utf8([x]):
                return False
        elif t is float:
            if not isfinite(x):
                return False
        elif t is int:
            if not _LO <= x <= _HI:
                return False
        elif t is dict or t is list:
            if not _fits(x, left - 1):
                return False
        elif t is not bool and x is not None:
            return False
    return True


def _where(value: Any, max_depth: int) -> FieldError:
    """The error naming the first value that is not plain data (or is nested too deep)."""
    todo: deque[tuple[tuple, Any, int]] = deque([((), value, 0)])
    while todo:
        path, v, depth = todo.popleft()
        kind = type(v)
        if kind in _CONTAINERS:
            if depth >= max_depth:
                return FieldError(f"nested deeper than {max_depth} levels", path)
            if kind is dict:
                for k in v:
                    if type(k) is not str or not _utf8([k]):
                        return FieldError(f"expected string keys, got {_show(k)}", path)
            pairs = v.items() if kind is dict else enumerate(v)
            todo.extend(((*path, k), x, depth + 1) for k, x in pairs)
        elif kind not in _ATOMS or (kind is float and not isfinite(v)) or \
                (kind is int and not _LO <= v <= _HI) or (kind is str and not _utf8([v])):
            return FieldError("expected plain data (null, true/false, a finite number, a "
                              f"string, an array or a map), got {_show(v)}", path)
    return FieldError(f"nested deeper than {max_depth} levels")


def _show(v: Any) -> str:
    from bus.schema.brief import brief

    return brief(v)
