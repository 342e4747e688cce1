"""Plain data: the values that may travel in a field whose inside another package reads (an
agent's memory, a world snapshot, an intention), checked only for what every reader and
writer of it relies on: null, booleans, integers of at most 64 bits, finite floats, strings,
arrays and maps with string keys, nested at most ``max_depth`` levels. So such a value can
always be encoded again (msgpack stops at 512 levels), written to JSON (no NaN, no bytes) and
shown in a message."""

from __future__ import annotations

from collections import deque
from itertools import chain
from math import isfinite
from typing import Any

from schema.specs import FieldError, Spec

_ATOMS = frozenset({str, int, float, bool, type(None)})
_CONTAINERS = (dict, list)
_KINDS = _ATOMS | frozenset(_CONTAINERS)
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
        level = [value] if type(value) in _CONTAINERS else []
        if not level:
            return self._atom_ok(value)
        for _ in range(self.max_depth):
            items = list(chain.from_iterable(x.values() if type(x) is dict else x
                                             for x in level))
            kinds = set(map(type, items))
            if not _KINDS.issuperset(kinds) or (float in kinds and not all(
                    isfinite(x) for x in items if type(x) is float)) or \
                    (int in kinds and not all(_LO <= x <= _HI for x in items
                                              if type(x) is int)) or \
                    (str in kinds and not all(x.isascii() for x in items if type(x) is str)
                     and not _utf8(items)) or not _keys_ok(level):
                raise _where(value, self.max_depth)
            level = [x for x in items if type(x) in _CONTAINERS]
            if not level:
                return value
        raise _where(value, self.max_depth)

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


def _keys_ok(level: list) -> bool:
    keys = [k for x in level if type(x) is dict for k in x]
    return all(type(k) is str for k in keys) and _utf8(keys)


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
    from schema.brief import brief

    return brief(v)
