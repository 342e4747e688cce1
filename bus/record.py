"""The recorded form of a bus message: plain JSON-able data with a JSON Schema per kind, so a
run record (tools/records/run_record.py writes it as MCAP) opens in Foxglove and plays back on the
bus.

The form is the wire map itself (`{"kind", "env", <fields>}`, bus/codec.py) read from msgpack,
plus derived fields that only help a viewer and are dropped again on the way back: a
Percepts message gets `"self"`, the attributes of the agent's own `self` percept as an object
(`{"speed": 7.58, "limit": 15.0, ...}`), so a plot can address `.self.speed`.

    record = to_record(key, payload)       # raises CodecError naming the key
    payload = from_record(key, record)     # msgpack again, checked by bus.codec.decode
"""

from __future__ import annotations

from typing import Any

import msgpack

from bus.codec import decode, encode
from bus.errors import CodecError
from bus.fields import All, Rows, Tuple
from bus.kinds import MESSAGE_TYPES, field_specs
from bus.messages import Message
from bus.rows import unpacked_rows
from bus.schema import Bool, Int, ListOf, MapOf, Num, OneOf, Plain, Record, Spec, Str


def derived(kind: str) -> tuple[str, ...]:
    """The fields a record of ``kind`` adds to the wire form (its class's DERIVED, left out
    again by `from_record`)."""
    cls = MESSAGE_TYPES.get(kind)
    return tuple(cls.DERIVED) if cls is not None else ()


def to_record(key: str, payload: bytes) -> dict[str, Any]:
    """The JSON-able record of a payload received on `key` (the wire map plus derived fields).
    Only the map's shape is checked here; raises CodecError naming the key."""
    try:
        body = msgpack.unpackb(payload, raw=False, strict_map_key=True)
    except (ValueError, TypeError, msgpack.UnpackException) as exc:
        raise CodecError(key, f"malformed msgpack payload ({len(payload)} bytes): {exc}") from exc
    if not isinstance(body, dict) or not isinstance(body.get("env"), dict) \
            or body.get("kind") not in MESSAGE_TYPES:
        raise CodecError(key, f"not a bus message: {body!r:.80}")
    cls = MESSAGE_TYPES[body["kind"]]
    field = cls.PACKED
    if field and field in body:
        try:
            body[field] = unpacked_rows(body[field])
        except TypeError as exc:
            raise CodecError(key, f"{body['kind']}.{field}: {exc}") from exc
    for name, how in cls.DERIVED.items():
        body[name] = how.make(body)
    return body


def message_record(key: str, msg: Message) -> dict[str, Any]:
    """The record of a message object (what `to_record` gives for its encoded payload)."""
    return to_record(key, encode(msg))


def from_record(key: str, record: dict[str, Any]) -> bytes:
    """The bus payload of a record, checked as a receiver would; raises CodecError."""
    if not isinstance(record, dict):
        raise CodecError(key, f"expected a record map, got {type(record).__name__}")
    drop = derived(str(record.get("kind")))
    body = {k: v for k, v in record.items() if k not in drop}
    try:
        payload = msgpack.packb(body, use_bin_type=True)
    except (TypeError, ValueError, OverflowError) as exc:
        raise CodecError(key, f"record not msgpack-able: {exc}") from exc
    decode(key, payload)
    return payload


_ATOM = {"type": ["string", "number"]}
_ROWS = {"type": "array", "items": {"type": "array", "items": _ATOM}}
_ENVELOPE = {"type": "object", "properties": {
    "v": {"type": "integer"}, "run": {"type": "string"}, "cycle": {"type": "integer"},
    "sender": {"type": "string"}, "sent_ns": {"type": "integer"}}}


def json_schema(kind: str) -> dict[str, Any]:
    """The JSON Schema of a kind's records (Foxglove reads it to offer the fields)."""
    cls = MESSAGE_TYPES.get(kind)
    if cls is None:
        raise CodecError(f"<schema {kind}>",
                         f"unknown message kind; known: {sorted(MESSAGE_TYPES)}")
    props: dict[str, Any] = {"kind": {"type": "string", "const": kind}, "env": _ENVELOPE}
    props.update({name: _json(spec) for name, spec, _ in field_specs(cls)})
    props.update({name: how.schema for name, how in cls.DERIVED.items()})
    return {"$schema": "http://json-schema.org/draft-07/schema#", "title": f"teleo.{kind}",
            "type": "object", "properties": props, "required": ["kind", "env"]}


def _json(spec: Spec) -> dict[str, Any]:
    """The JSON Schema of a field's records, from its spec (what a viewer offers)."""
    kind = type(spec)
    if kind is All:
        return _json(spec.specs[-1])
    if kind is Tuple:
        return _json(spec.spec)
    simple = {Str: "string", Int: "integer", Num: "number", Bool: "boolean", Record: "object",
              MapOf: "object"}.get(kind)
    if simple:
        return {"type": simple}
    if kind is OneOf:
        return {"enum": list(spec.choices)}
    if kind is Rows:
        return _ROWS
    if kind is ListOf:
        return {"type": "array", "items": _json(spec.item)}
    if kind is Plain and spec.top is not None:
        return {"type": "object" if spec.top is dict else "array"}
    return {}
