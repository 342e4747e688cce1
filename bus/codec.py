"""msgpack codec for bus messages: `encode(msg) -> bytes`, `decode(key, data) -> msg`.

Wire form: one msgpack map with string keys only,
`{"kind": "Percepts", "env": {"v", "run", "cycle", "sender", "sent_ns"}, <fields>...}`.
A reader ignores fields it does not know (a minor version may only add fields) and
rejects any other major version (`Envelope.v`). Every failure raises CodecError naming
the key and what is wrong; receivers log it and drop the payload.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import MISSING, fields
from typing import Any

import msgpack

from bus import keys
from bus.errors import CodecError
from bus.messages import GOAL_OPS, MESSAGE_TYPES, SCHEMA_VERSION, Envelope, Message

_ATOM_TYPES = frozenset({str, int, float})  # exact types: bool and None are refused


def encode(msg: Message) -> bytes:
    """Serialise a message to msgpack bytes (raises CodecError if a field is not msgpack-able)."""
    kind = getattr(msg, "KIND", None)
    if kind not in MESSAGE_TYPES or type(msg) is not MESSAGE_TYPES[kind]:
        raise CodecError(f"<encode {type(msg).__name__}>", "not a bus message")
    env = msg.env
    body: dict[str, Any] = {
        "kind": kind,
        "env": {"v": env.v, "run": env.run, "cycle": env.cycle, "sender": env.sender,
                "sent_ns": env.sent_ns},
    }
    for f in fields(msg):
        if f.name != "env":
            body[f.name] = getattr(msg, f.name)
    try:
        return msgpack.packb(body, use_bin_type=True)
    except (TypeError, ValueError, OverflowError) as exc:
        raise CodecError(f"<encode {kind}>", f"not msgpack-able: {exc}") from exc


def decode(key: str, data: bytes) -> Message:
    """Parse and validate a payload received on `key`; raises CodecError on any problem."""
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
    allowed = keys.kind_of_key(key)
    if allowed and kind not in allowed:
        raise CodecError(key, f"wrong message kind {kind!r} for this key "
                              f"(expected {' or '.join(sorted(allowed))})")
    values: dict[str, Any] = {"env": env}
    for f in fields(cls):
        if f.name == "env":
            continue
        if f.name in body:
            values[f.name] = _check(key, kind, f.name, body[f.name])
        elif f.default is not MISSING:
            values[f.name] = f.default
        else:
            raise CodecError(key, f"{kind} lacks field {f.name!r}")
    if kind == "GoalRequest" and values["op"] not in GOAL_OPS:
        raise CodecError(key, f"GoalRequest.op {values['op']!r} not one of {GOAL_OPS}")
    return cls(**values)


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


def _check(key: str, kind: str, name: str, value: Any) -> Any:
    checker = _FIELD_CHECKS.get(name, _any)
    try:
        return checker(value)
    except TypeError as exc:
        raise CodecError(key, f"{kind}.{name}: {exc}") from exc


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
    """A tuple of neutral-form lists whose items are str, int or float (never bool/None)."""
    atoms_only = _ATOM_TYPES.issuperset
    for row in _list(v):
        if type(row) is not list or not atoms_only(map(type, row)):
            raise TypeError(f"expected arrays of str, int or float, found item {row!r:.60}")
    return tuple(v)


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
    "op": _str, "goal": _str, "priority": _int, "goal_id": _str,
    "ok": _bool, "reason": _str, "goals": _dict_rows,
    "process": _str, "compute_ms": _float, "late": _int, "event": _dict,
}
