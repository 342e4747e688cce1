"""msgpack codec for bus messages: `encode(msg) -> bytes`, `decode(key, data) -> msg`.

Wire form: one msgpack map with string keys only,
`{"kind": "Percepts", "env": {"v", "run", "cycle", "sender", "sent_ns"}, <fields>...}`.
`env.v` is the protocol's major version (bus/messages.py SCHEMA_VERSION), carried by every
message. A reader ignores fields it does not know (a minor change may only add fields, and
keeps `v`) and refuses any other major version with an error naming both. Every field is
checked against its kind's schema (declared with it, bus/messages.py), by the kind's compiled
check (bus/compiled.py), before the message is made. Every failure raises CodecError naming
the key, the field and what is wrong
(`teleo/r/agent/ME/goal-list: GoalList.goals[0].id: expected a string, got []`); receivers
log it and drop the payload.

Packed rows: the rows of `Percepts.percepts` and `Beliefs.beliefs` travel one msgpack bin a
row, and a row seen in the last message on a key decodes to the same list (bus/rows.py).
"""

from __future__ import annotations

from dataclasses import MISSING
from functools import lru_cache
from typing import Any

import msgpack

from bus import keys
from bus.compiled import Compiled, compile_kind
from bus.errors import CodecError
from bus.fields import ENVELOPE
from bus.kinds import MESSAGE_TYPES, Fresh
from bus.messages import SCHEMA_VERSION, Envelope, Message
from bus.rows import pack_rows, packer, unpack_rows
from bus.schema import FieldError, brief


def encode(msg: Message) -> bytes:
    """Serialise a message to msgpack bytes (raises CodecError if a field is not msgpack-able)."""
    kind = _compiled(type(msg))  # exact classes only: a subclass is not a bus message
    if kind is None:
        raise CodecError(f"<encode {type(msg).__name__}>", "not a bus message")
    env = msg.env
    body: dict[str, Any] = {
        "kind": msg.KIND,
        "env": {"v": env.v, "run": env.run, "cycle": env.cycle, "sender": env.sender,
                "sent_ns": env.sent_ns},
    }
    for name in kind.names:
        body[name] = getattr(msg, name)
    packed = kind.packed
    try:
        if packed:
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
    allowed = _kinds_of_key(key, len(MESSAGE_TYPES))
    if allowed and kind not in allowed:
        raise CodecError(key, f"wrong message kind {kind!r} for this key "
                              f"(expected {' or '.join(sorted(allowed))})")
    values = check_fields(key, cls, body)
    values["env"] = env
    return cls(**values)


def check_fields(key: str, cls: type, body: dict) -> dict[str, Any]:
    """The checked field values of a ``cls`` message's wire map received on ``key``: the
    kind's compiled check (bus/compiled.py) when every field is there (as every writer sends
    them), else the field-by-field walk that fills in defaults; raises CodecError."""
    kind = _compiled(cls)
    if kind is None:
        raise CodecError(key, f"not a bus message kind: {cls.__name__}")
    values = kind.check(key, body, unpack_rows)
    return walk_fields(key, kind, body) if values is None else values


def walk_fields(key: str, kind: Compiled, body: dict) -> dict[str, Any]:
    """The checked field values of a ``kind`` message, one field's spec after another, with
    defaults for absent optional fields (what the compiled check does for a whole message)."""
    values: dict[str, Any] = {}
    name_of = kind.cls.KIND
    for name, spec, default in kind.fields:
        if name in body:
            try:
                values[name] = unpack_rows(key, body[name]) if name == kind.packed else \
                    spec.check(body[name])
            except FieldError as exc:
                raise CodecError(key, f"{name_of}.{exc.within(name)}") from None
            except TypeError as exc:   # a packed row (bus/rows.py)
                raise CodecError(key, f"{name_of}.{name}: {exc}") from None
        elif isinstance(default, Fresh):
            values[name] = default.make()   # a new empty map for each message
        elif default is not MISSING:
            values[name] = default
        else:
            raise CodecError(key, f"{name_of} lacks field {name!r}")
    return values


def _compiled(cls: type) -> Compiled | None:
    """The compiled form of a declared kind's class (made on first use), else None."""
    kind = _KINDS.get(cls)
    if kind is None and MESSAGE_TYPES.get(getattr(cls, "KIND", None)) is cls:
        kind = _KINDS[cls] = compile_kind(cls)
    return kind


_KINDS: dict[type, Compiled] = {}


@lru_cache(maxsize=4096)
def _kinds_of_key(key: str, declared: int) -> frozenset[str]:
    """keys.kind_of_key, memoised per number of declared kinds: a process sees the same few
    keys every cycle."""
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
