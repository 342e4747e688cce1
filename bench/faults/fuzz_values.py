"""Structured inputs for the fuzz drill (bench/faults/fuzz.py): valid messages mutated field by
field.

`mutate(value, rng, pool)` takes a valid message as plain data (a world event, a memory, a
world state's fields...) and makes 1 to 3 edits at random places in it: a field's value
replaced by junk (every type: null, bools, 64-bit edges and beyond, NaN, infinities, huge and
tiny floats, long and odd strings, bytes, unhashable lists and maps, deep nesting), by another
valid value of the same field from `pool` (so many mutants are still valid), a number pushed
out of range or turned int/float, a field dropped, an unknown field added, a value wrapped
in a list. `wire(value)` is the msgpack body of such a value, when msgpack can carry it.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from typing import Any

import msgpack


def deep(levels: int, leaf: Any = 0, kind: str = "list") -> Any:
    """``leaf`` nested ``levels`` deep in lists (or maps)."""
    value = leaf
    for _ in range(levels):
        value = [value] if kind == "list" else {"k": value}
    return value


JUNK: tuple[Any, ...] = (
    None, True, False, 0, 1, -1, 2**31, 2**53 + 1, 2**63 - 1, 2**63, 2**64 - 1, -(2**63),
    -(2**63) - 1, 10**30, 0.0, -0.0, 0.5, 1e-320, 1e308, -1e308, math.nan, math.inf, -math.inf,
    "", " ", "x", "ME", "NIL", "T", "\x00", "\u00e9", "\u202e", "a b", "S" + "9" * 40,
    "X" * 300, "Y" * 70_000, "?x", "(a)", [], [[]], [1, 2], ["x"], [None], {}, {"k1": []},
    {"kind": "x"}, {"": 1}, [[1, [2, [3]]]], b"", b"\x00\xff", deep(60), deep(600),
    deep(40, kind="map"), deep(300, kind="map"), [1] * 2000, {f"k{i}": i for i in range(300)},
)
"""Values of every type and size, put in any field."""


def junk(rng: random.Random) -> Any:
    return rng.choice(JUNK)


def _nudge(value: int | float, rng: random.Random) -> Any:
    """A number pushed out of range, made the other numeric type, or negated."""
    return rng.choice([value * 10**6, -value - 1, value + 0.5, float(value) if
                       isinstance(value, int) else int(value) if math.isfinite(value) else 0,
                       value + 1, -(2**63) if value >= 0 else 2**64 - 1])


def _paths(value: Any, prefix: tuple = ()) -> list[tuple]:
    """Every path to a node of ``value`` (maps and lists) down to 24 levels, itself first."""
    out = [prefix]
    if len(prefix) >= 24:
        return out
    if isinstance(value, dict):
        for k, v in value.items():
            out += _paths(v, (*prefix, k))
    elif isinstance(value, list) and len(value) <= 64:
        for i, v in enumerate(value):
            out += _paths(v, (*prefix, i))
    return out


def _get(value: Any, path: tuple) -> Any:
    for part in path:
        value = value[part]
    return value


def _put(value: Any, path: tuple, new: Any) -> Any:
    """``value`` with the node at ``path`` replaced (copies along the path only)."""
    if not path:
        return new
    head, rest = path[0], path[1:]
    copy = dict(value) if isinstance(value, dict) else list(value)
    copy[head] = _put(value[head], rest, new)
    return copy


def _drop(value: Any, path: tuple) -> Any:
    """``value`` without the node at ``path`` (a map's key or a list's item)."""
    parent = _get(value, path[:-1])
    if isinstance(parent, dict):
        copy = {k: v for k, v in parent.items() if k != path[-1]}
    else:
        copy = [v for i, v in enumerate(parent) if i != path[-1]]
    return _put(value, path[:-1], copy)


def _edit(value: Any, rng: random.Random, pool: Mapping[str, list]) -> Any:
    path = rng.choice(_paths(value))
    node = _get(value, path)
    op = rng.randrange(10)
    key = path[-1] if path else None
    if op <= 2:
        return _put(value, path, junk(rng))
    if op <= 4 and isinstance(key, str) and pool.get(key):
        return _put(value, path, rng.choice(pool[key]))
    if op == 5 and isinstance(node, int | float) and not isinstance(node, bool):
        return _put(value, path, _nudge(node, rng))
    if op == 6 and path:
        return _drop(value, path)
    if op == 7 and isinstance(node, dict):
        name = rng.choice(["colour", "x", "kind", "id", "", "extra", "k1", "speed"])
        return _put(value, path, {**node, name: junk(rng) if rng.random() < 0.5 else 1})
    if op == 8:
        return _put(value, path, [node])
    if isinstance(node, str) and node:
        cut = rng.randrange(len(node))
        return _put(value, path, rng.choice([node[:cut], node + node, node.upper(),
                                              node[:cut] + "\u0661" + node[cut:]]))
    return _put(value, path, junk(rng))


def mutate(value: Any, rng: random.Random, pool: Mapping[str, list] | None = None) -> Any:
    """1 to 3 edits of ``value`` (see the module); ``pool``: valid values per field name."""
    for _ in range(rng.randint(1, 3)):
        value = _edit(value, rng, pool or {})
    return value


def swap(value: dict, rng: random.Random, pool: Mapping[str, list]) -> dict:
    """``value`` with one or two of its fields given another value seen for that field
    (mostly still valid: the accepted side of a reader)."""
    names = [k for k in value if pool.get(k)]
    out = dict(value)
    for name in rng.sample(names, min(len(names), rng.randint(1, 2))):
        out[name] = rng.choice(pool[name])
    return out


def pool_of(values: list[Any]) -> dict[str, list]:
    """Field name -> the atoms and small values seen under that name in ``values``."""
    out: dict[str, list] = {}

    def visit(v: Any) -> None:
        if isinstance(v, dict):
            for k, x in v.items():
                if not isinstance(x, dict | list) or len(x) <= 4:
                    bucket = out.setdefault(k, [])
                    if len(bucket) < 50 and x not in bucket:
                        bucket.append(x)
                visit(x)
        elif isinstance(v, list):
            for x in v[:64]:
                visit(x)

    for v in values:
        visit(v)
    return out


def wire(value: Any) -> bytes | None:
    """The msgpack bytes of ``value``, or None when msgpack cannot carry it (an integer
    beyond 64 bits, nesting past msgpack's limit, a lone surrogate)."""
    try:
        return msgpack.packb(value, use_bin_type=True)
    except (TypeError, ValueError, OverflowError, UnicodeEncodeError):
        return None


def fields_of(value: Any, out: set[str] | None = None, depth: int = 0) -> set[str]:
    """Every key and every short string of ``value`` (what a refusal may name)."""
    out = set() if out is None else out
    if depth > 40:
        return out
    if isinstance(value, dict):
        for k, v in value.items():
            if isinstance(k, str):
                out.add(k)
            fields_of(v, out, depth + 1)
    elif isinstance(value, list):
        for v in value[:100]:
            fields_of(v, out, depth + 1)
    elif isinstance(value, str) and len(value) <= 64:
        out.add(value)
    return out
