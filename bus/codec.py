"""msgpack codec for bus messages: `encode(msg) -> bytes`, `decode(key, data) -> msg`.

Wire form: one msgpack map with string keys only,
`{"kind": "Percepts", "env": {"v", "run", "cycle", "sender", "sent_ns"}, <fields>...}`.
A reader ignores fields it does not know (a minor version may only add fields) and
rejects any other major version (`Envelope.v`). Every failure raises CodecError naming
the key and what is wrong; receivers log it and drop the payload.

Packed rows: the rows of `Percepts.percepts` and `Beliefs.beliefs` travel each as a msgpack
bin holding that row's own msgpack bytes (a reader also takes plain arrays, and a mix). A
reader decodes a row whose bytes equal one of the last message's on the same key to that very
list, without reading it again; nobody mutates a decoded row, so the engine takes a row it has
seen as unchanged (agents/lang/shared_rows.py; docs/bus.md, "Packed rows"). A writer packs a
row that is the same object as one it sent last time in the same field to the same bytes
without packing it again.
"""

from __future__ import annotations

import gc
import threading
from collections.abc import Callable
from dataclasses import MISSING, fields
from functools import lru_cache
from itertools import chain, compress, repeat
from math import isfinite
from operator import is_, ne
from typing import Any

import msgpack

from bus import keys
from bus.errors import CodecError
from bus.messages import GOAL_OPS, MESSAGE_TYPES, SCHEMA_VERSION, Envelope, Message

_ATOM_TYPES = frozenset({str, int, float})  # exact types: bool and None are refused
_LIST_ONLY = frozenset({list})
_local = threading.local()  # one msgpack.Packer per thread (publish may run on zenoh threads)


def encode(msg: Message) -> bytes:
    """Serialise a message to msgpack bytes (raises CodecError if a field is not msgpack-able)."""
    spec = _SPECS.get(type(msg))  # exact classes only: a subclass is not a bus message
    if spec is None:
        raise CodecError(f"<encode {type(msg).__name__}>", "not a bus message")
    env = msg.env
    body: dict[str, Any] = {
        "kind": msg.KIND,
        "env": {"v": env.v, "run": env.run, "cycle": env.cycle, "sender": env.sender,
                "sent_ns": env.sent_ns},
    }
    for name, _check, _default in spec:
        body[name] = getattr(msg, name)
    packed = PACKED.get(msg.KIND)
    try:
        if packed is not None:
            body[packed] = _pack_rows(body[packed], (msg.KIND, getattr(msg, "agent", "")))
        return _packer().pack(body)
    except (TypeError, ValueError, OverflowError) as exc:
        raise CodecError(f"<encode {msg.KIND}>", f"not msgpack-able: {exc}") from exc


def decode(key: str, data: bytes) -> Message:
    """Parse and validate a payload received on `key`; raises CodecError on any problem.

    The garbage collector is paused meanwhile (decoding makes thousands of objects and no
    reference cycle: each burst would otherwise start collections walking the process's
    young objects)."""
    if not gc.isenabled():
        return _decode(key, data)
    gc.disable()
    try:
        return _decode(key, data)
    finally:
        gc.enable()


def _decode(key: str, data: bytes) -> Message:
    try:
        body = msgpack.unpackb(data, raw=False, strict_map_key=True)
    except (ValueError, TypeError, msgpack.UnpackException) as exc:
        raise CodecError(key, f"malformed msgpack payload ({len(data)} bytes): {exc}") from exc
    if not isinstance(body, dict):
        raise CodecError(key, f"expected a msgpack map, got {type(body).__name__}")
    env = _envelope(key, body.get("env"))
    kind = body.get("kind")
    cls = MESSAGE_TYPES.get(kind) if isinstance(kind, str) else None
    if cls is None:
        raise CodecError(key, f"unknown message kind {kind!r}")
    allowed = _kinds_of_key(key)
    if allowed and kind not in allowed:
        raise CodecError(key, f"wrong message kind {kind!r} for this key "
                              f"(expected {' or '.join(sorted(allowed))})")
    values = _fields(key, kind, _SPECS[cls], body)
    values["env"] = env
    if kind == "GoalRequest" and values["op"] not in GOAL_OPS:
        raise CodecError(key, f"GoalRequest.op {values['op']!r} not one of {GOAL_OPS}")
    return cls(**values)


def _fields(key: str, kind: str, spec: _Spec, body: dict) -> dict[str, Any]:
    """The checked field values of a `kind` message (defaults for absent optional fields)."""
    values: dict[str, Any] = {}
    name = ""
    packed = PACKED.get(kind)
    try:
        for name, check, default in spec:
            if name in body:
                values[name] = _unpack_rows(key, body[name]) if name == packed else \
                    check(body[name])
            elif isinstance(default, _Fresh):
                values[name] = default.make()   # a new empty map for each message
            elif default is not MISSING:
                values[name] = default
            else:
                raise CodecError(key, f"{kind} lacks field {name!r}")
    except TypeError as exc:
        raise CodecError(key, f"{kind}.{name}: {exc}") from exc
    return values


@lru_cache(maxsize=4096)
def _kinds_of_key(key: str) -> frozenset[str]:
    """keys.kind_of_key, memoised: a process sees the same few keys every cycle."""
    return keys.kind_of_key(key)


def _packer() -> msgpack.Packer:
    """This thread's Packer (autoreset: each `pack` returns the bytes of one object and
    leaves the packer empty, also after an error)."""
    packer = getattr(_local, "packer", None)
    if packer is None:
        packer = _local.packer = msgpack.Packer(use_bin_type=True, autoreset=True)
    return packer


def _envelope(key: str, env: Any) -> Envelope:
    if not isinstance(env, dict):
        raise CodecError(key, f"missing or malformed envelope: {env!r:.80}")
    v = env.get("v")
    if v != SCHEMA_VERSION:
        raise CodecError(key, f"unknown schema version {v!r} (this reader knows {SCHEMA_VERSION})")
    try:
        return Envelope(v=v, run=_str(env["run"]), cycle=_int(env["cycle"]),
                        sender=_str(env["sender"]), sent_ns=_int(env["sent_ns"]))
    except (KeyError, TypeError) as exc:
        raise CodecError(key, f"malformed envelope {env!r:.120}: {exc}") from exc


def _str(v: Any) -> str:
    if not isinstance(v, str):
        raise TypeError(f"expected str, got {type(v).__name__}")
    return v


def _int(v: Any) -> int:
    if not isinstance(v, int) or isinstance(v, bool):
        raise TypeError(f"expected int, got {type(v).__name__}")
    return v


def _float(v: Any) -> float:
    if not isinstance(v, (int, float)) or isinstance(v, bool):
        raise TypeError(f"expected number, got {type(v).__name__}")
    return float(v)


def _bool(v: Any) -> bool:
    if not isinstance(v, bool):
        raise TypeError(f"expected bool, got {type(v).__name__}")
    return v


def _dict(v: Any) -> dict:
    if not isinstance(v, dict):
        raise TypeError(f"expected map, got {type(v).__name__}")
    return v


def _list(v: Any) -> list:
    if not isinstance(v, list):
        raise TypeError(f"expected array, got {type(v).__name__}")
    return v


def _rows(v: Any) -> tuple:
    """A tuple of neutral-form lists whose items are str, int or float (never bool/None) and
    whose floats are finite (NaN and infinities would poison every comparison downstream).

    Checked in C-level passes over the types and one over the floats; only a bad payload
    takes the row-by-row loop that names the offending row.
    """
    rows = _list(v)
    if _LIST_ONLY.issuperset(map(type, rows)):
        atoms = list(chain.from_iterable(rows))
        types = list(map(type, atoms))
        if _ATOM_TYPES.issuperset(types) and \
                all(map(isfinite, compress(atoms, map(is_, types, repeat(float))))):
            return tuple(rows)
    atoms_only = _ATOM_TYPES.issuperset
    for row in rows:
        if type(row) is not list or not atoms_only(map(type, row)):
            raise TypeError(f"expected arrays of str, int or float, found item {row!r:.60}")
        bad = [a for a in row if type(a) is float and not isfinite(a)]
        if bad:
            raise TypeError(f"expected finite numbers, found {bad[0]} in item {row!r:.60}")
    raise TypeError("expected arrays of str, int or float")  # not reached: some row failed


PACKED = {"Percepts": "percepts", "Beliefs": "beliefs"}
"""The field whose rows travel packed, per kind (see the module's docstring)."""


def _pack_rows(rows: Any, slot: tuple) -> list[bytes]:
    """Each row as its own msgpack bytes; a row sent last time in ``slot`` as the same object
    keeps its bytes (rows are never mutated once sent)."""
    sent = getattr(_local, "sent", None)
    if sent is None:
        sent = _local.sent = {}
    last = sent.get(slot)
    pack = _packer().pack
    ids = list(map(id, rows))
    if last:
        out = [h[1] if h is not None and h[0] is r else pack(r)
               for h, r in zip(map(last.get, ids), rows, strict=True)]
    else:
        out = list(map(pack, rows))
    sent[slot] = dict(zip(ids, zip(rows, out, strict=True), strict=True))
    return out


def shared_rows(kind: str, agent: str, rows: Any) -> tuple:
    """``rows`` as a receiver of the packed field would get them, for a message handed over in
    memory (agents/processes/shared.py): each row whose bytes equal those of a row last given
    here for (``kind``, ``agent``) is replaced by that row. Encoding the message afterwards
    packs no row again."""
    memo = getattr(_local, "interned", None)
    if memo is None:
        memo = _local.interned = {}
    slot = (kind, agent)
    last = memo.get(slot, {})
    data = _pack_rows(rows, slot)
    out = tuple(last.get(b, r) for b, r in zip(data, rows, strict=True))
    memo[slot] = dict(zip(data, out, strict=True))
    _local.sent[slot] = dict(zip(map(id, out), zip(out, data, strict=True), strict=True))
    return out


def _unpack_rows(key: str, v: Any) -> tuple:
    """The rows of a packed field received on ``key``, checked as ``_rows`` checks them; a
    row of the same bytes as one in the last message on ``key`` is that message's list.

    Kept per key: the last message's items and rows, and bytes -> row of the rows seen lately
    (rebuilt when it holds twice as many as a message). Items are first compared position by
    position with the last message's (rows mostly stay where they were), then looked up."""
    items = _list(v)
    seen = getattr(_local, "seen", None)
    if seen is None:
        seen = _local.seen = {}
    was = seen.get(key)
    if was is not None and was[0] == items:  # the very same rows: last message's tuple
        return was[1]
    n = len(items)
    by: dict = was[2] if was is not None else {}
    at = list(compress(range(n), map(ne, items, was[0]))) \
        if was is not None and len(was[0]) == n else None
    if at is not None and len(at) * 4 <= n:  # a few rows changed: look only those up
        got = list(was[1])
        for i in at:
            b = items[i]
            got[i] = by.get(b) if type(b) is bytes else None
        new = [i for i in at if got[i] is None]
    else:
        got = _known(by, items)
        new = list(compress(range(n), map(is_, got, repeat(None))))
    if new:
        fresh = _rows(_unpacked_all([items[i] for i in new]))
        for i, row in zip(new, fresh, strict=True):
            got[i] = row
        if len(new) * 4 <= n:
            by.update((items[i], got[i]) for i in new if type(items[i]) is bytes)
        else:
            by = _by_bytes(items, got)
    if len(by) > 2 * n + 16:
        by = _by_bytes(items, got)
    out = tuple(got)
    seen[key] = (items, out, by)
    return out


def _by_bytes(items: list, rows: list) -> dict:
    """bytes -> row, for the items given as bytes (plain arrays are left out)."""
    try:
        return dict(zip(items, rows, strict=True))
    except TypeError:  # a plain array among the items (unhashable)
        return {b: r for b, r in zip(items, rows, strict=True) if type(b) is bytes}


def _known(last: dict, items: list) -> list:
    """The row in ``last`` of each item given as bytes, else None."""
    try:
        return list(map(last.get, items))
    except TypeError:  # a plain array among the items (unhashable)
        return [last.get(b) if type(b) is bytes else None for b in items]


_BYTES_ONLY = frozenset({bytes})


def _unpacked_all(items: list) -> list:
    """``_unpacked`` of each item: one C-level pass when they are all bytes and all good."""
    if _BYTES_ONLY.issuperset(map(type, items)):
        try:
            return list(map(msgpack.unpackb, items))
        except (ValueError, TypeError, msgpack.UnpackException):
            pass  # name the bad row below
    return list(map(_unpacked, items))


def _unpacked(item: Any) -> Any:
    """One row of a packed field: its own msgpack bytes read, or a plain array as it is."""
    if type(item) is not bytes:
        return item
    try:
        return msgpack.unpackb(item, raw=False, strict_map_key=True)
    except (ValueError, TypeError, msgpack.UnpackException) as exc:
        raise TypeError(f"malformed packed row ({len(item)} bytes): {exc}") from exc


def unpacked_rows(v: Any) -> Any:
    """A packed field's rows as plain arrays (records, tools); anything else as it is."""
    return [_unpacked(r) for r in v] if isinstance(v, list) else v


def _dict_rows(v: Any) -> tuple:
    for row in _list(v):
        if not isinstance(row, dict):
            raise TypeError(f"expected array of maps, found item {row!r:.60}")
    return tuple(v)


def _any(v: Any) -> Any:
    return v


_FIELD_CHECKS: dict[str, Callable[[Any], Any]] = {
    "snapshot": _dict, "outcomes": _dict, "events": _list, "agent": _str,
    "percepts": _rows, "beliefs": _rows, "actions": _rows, "decision": _dict,
    "op": _str, "goal": _str, "priority": _int, "goal_id": _str, "force": _bool,
    "ok": _bool, "reason": _str, "goals": _dict_rows,
    "process": _str, "compute_ms": _float, "late": _int, "event": _dict, "memory": _dict,
    "outcome": _dict,
}

_KIND_FIELD_CHECKS: dict[tuple[str, str], Callable[[Any], Any]] = {
    ("Percepts", "outcomes"): _dict_rows,   # a list of outcome maps (WorldState's is a map)
}

class _Fresh:
    """The default of a field declared with a default_factory (made anew per message)."""

    def __init__(self, make: Callable[[], Any]) -> None:
        self.make = make


_Spec = tuple[tuple[str, Callable[[Any], Any], Any], ...]

_SPECS: dict[type, _Spec] = {
    cls: tuple((f.name, _KIND_FIELD_CHECKS.get((cls.KIND, f.name),
                                               _FIELD_CHECKS.get(f.name, _any)),
                _Fresh(f.default_factory) if f.default_factory is not MISSING else f.default)
               for f in fields(cls) if f.name != "env")
    for cls in MESSAGE_TYPES.values()
}
"""Per message class: (field name, checker, default or MISSING) for every field but env."""
