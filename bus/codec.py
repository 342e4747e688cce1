"""msgpack codec for bus messages: `encode(msg) -> bytes`, `decode(key, data) -> msg`.

Wire form: one msgpack map with string keys only,
`{"kind": "Percepts", "env": {"v", "run", "cycle", "sender", "sent_ns"}, <fields>...}`.
`env.v` is the protocol's major version (bus/messages.py SCHEMA_VERSION), carried by every
message. A reader ignores fields it does not know (a minor change may only add fields, and
keeps `v`) and refuses any other major version with an error naming both. Every field is
checked against its kind's schema (bus/fields.py) before the message is made. Every
failure raises CodecError naming the key, the field and what is wrong
(`teleo/r/agent/ME/goal-list: GoalList.goals[0].id: expected a string, got []`);
receivers log it and drop the payload.

Packed rows: the rows of `Percepts.percepts` and `Beliefs.beliefs` travel one msgpack bin a
row, and a row seen in the last message on a key decodes to the same list (bus/rows.py).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import MISSING, fields
from functools import lru_cache
from typing import Any

import msgpack

from bus import keys
from bus.errors import CodecError
from bus.fields import ENVELOPE, FIELDS
from bus.messages import MESSAGE_TYPES, SCHEMA_VERSION, Envelope, Message
from bus.rows import PACKED, pack_rows, packer, unpack_rows
from bus.schema import FieldError, brief


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
            body[packed] = pack_rows(body[packed], (msg.KIND, getattr(msg, "agent", "")))
        return packer().pack(body)
    except (TypeError, ValueError, OverflowError) as exc:
        raise CodecError(f"<encode {msg.KIND}>", f"not msgpack-able: {exc}") from exc


def decode(key: str, data: bytes) -> Message:
    """Parse and validate a payload received on `key`; raises CodecError on any problem.
    (Decoding makes thousands of objects and no reference cycle; when the collector runs is
    the process's policy, bus/collector.py, not the codec's.)"""
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
        raise CodecError(key, f"unknown message kind {brief(kind)}")
    allowed = _kinds_of_key(key)
    if allowed and kind not in allowed:
        raise CodecError(key, f"wrong message kind {kind!r} for this key "
                              f"(expected {' or '.join(sorted(allowed))})")
    values = _fields(key, kind, _SPECS[cls], body)
    values["env"] = env
    return cls(**values)


def _fields(key: str, kind: str, spec: _Spec, body: dict) -> dict[str, Any]:
    """The checked field values of a `kind` message (defaults for absent optional fields)."""
    values: dict[str, Any] = {}
    packed = PACKED.get(kind)
    for name, check, default in spec:
        if name in body:
            try:
                values[name] = unpack_rows(key, body[name]) if name == packed else \
                    check(body[name])
            except FieldError as exc:
                raise CodecError(key, f"{kind}.{exc.within(name)}") from None
            except TypeError as exc:   # a packed row (bus/rows.py)
                raise CodecError(key, f"{kind}.{name}: {exc}") from None
        elif isinstance(default, _Fresh):
            values[name] = default.make()   # a new empty map for each message
        elif default is not MISSING:
            values[name] = default
        else:
            raise CodecError(key, f"{kind} lacks field {name!r}")
    return values


@lru_cache(maxsize=4096)
def _kinds_of_key(key: str) -> frozenset[str]:
    """keys.kind_of_key, memoised: a process sees the same few keys every cycle."""
    return keys.kind_of_key(key)


def _envelope(key: str, env: Any) -> Envelope:
    if not isinstance(env, dict):
        raise CodecError(key, f"missing or malformed envelope: {brief(env)}")
    v = env.get("v")
    if type(v) is not int:
        raise CodecError(key, f"unknown schema version {brief(v)}: expected the major version "
                              f"as an integer (this reader's is {SCHEMA_VERSION})")
    if v != SCHEMA_VERSION:
        raise CodecError(key, f"unknown schema version {v}: this reader speaks major version "
                              f"{SCHEMA_VERSION} only (a minor change only adds fields, which "
                              f"a reader ignores, and keeps the version)")
    try:
        ENVELOPE.check(env)
    except FieldError as exc:
        raise CodecError(key, f"malformed envelope: {exc.within('env')}") from None
    return Envelope(v, env["run"], env["cycle"], env["sender"], env["sent_ns"])


class _Fresh:
    """The default of a field declared with a default_factory (made anew per message)."""

    def __init__(self, make: Callable[[], Any]) -> None:
        self.make = make


_Spec = tuple[tuple[str, Callable[[Any], Any], Any], ...]

_SPECS: dict[type, _Spec] = {
    cls: tuple((f.name, FIELDS[cls.KIND][f.name].check,
                _Fresh(f.default_factory) if f.default_factory is not MISSING else f.default)
               for f in fields(cls) if f.name != "env")
    for cls in MESSAGE_TYPES.values()
}
"""Per message class: (field name, its spec's check (bus/fields.py), default or MISSING) for
every field but env."""
