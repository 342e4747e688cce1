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
from bus.messages import MESSAGE_TYPES, Message
from bus.rows import PACKED, unpacked_rows

DERIVED: dict[str, tuple[str, ...]] = {"Percepts": ("self",)}
"""Per kind, the fields a record adds to the wire form (left out again by `from_record`)."""


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
    field = PACKED.get(body["kind"])
    if field in body:
        try:
            body[field] = unpacked_rows(body[field])
        except TypeError as exc:
            raise CodecError(key, f"{body['kind']}.{field}: {exc}") from exc
    if body["kind"] == "Percepts":
        body["self"] = _self_attrs(body.get("agent"), body.get("percepts"))
    return body


def message_record(key: str, msg: Message) -> dict[str, Any]:
    """The record of a message object (what `to_record` gives for its encoded payload)."""
    return to_record(key, encode(msg))


def from_record(key: str, record: dict[str, Any]) -> bytes:
    """The bus payload of a record, checked as a receiver would; raises CodecError."""
    if not isinstance(record, dict):
        raise CodecError(key, f"expected a record map, got {type(record).__name__}")
    drop = DERIVED.get(str(record.get("kind")), ())
    body = {k: v for k, v in record.items() if k not in drop}
    try:
        payload = msgpack.packb(body, use_bin_type=True)
    except (TypeError, ValueError, OverflowError) as exc:
        raise CodecError(key, f"record not msgpack-able: {exc}") from exc
    decode(key, payload)
    return payload


def _self_attrs(agent: Any, percepts: Any) -> dict[str, Any]:
    """Attributes of the `(self AGENT ...)` percept as an object; {} when there is none."""
    for p in percepts if isinstance(percepts, list) else ():
        if isinstance(p, list) and len(p) >= 2 and p[0] == "self" and p[1] == agent:
            return {str(p[i]): p[i + 1] for i in range(2, len(p) - 1, 2)}
    return {}


_ATOM = {"type": ["string", "number"]}
_ROWS = {"type": "array", "items": {"type": "array", "items": _ATOM}}
_MAPS = {"type": "array", "items": {"type": "object"}}
_FIELDS: dict[str, dict[str, Any]] = {
    "snapshot": {"type": "object", "description": "the world's snapshot dict of this cycle"},
    "outcomes": {"type": "object"}, "events": _MAPS, "agent": {"type": "string"},
    "percepts": _ROWS, "beliefs": _ROWS, "actions": _ROWS,
    "decision": {"type": "object", "description": "goals, path, actions, why (Decision)"},
    "op": {"type": "string"}, "goal": {"type": "string"}, "priority": {"type": "integer"},
    "goal_id": {"type": "string"}, "ok": {"type": "boolean"}, "reason": {"type": "string"},
    "goals": _MAPS, "process": {"type": "string"}, "compute_ms": {"type": "number"},
    "late": {"type": "integer"}, "event": {"type": "object"},
    "self": {"type": "object", "description": "derived: the agent's own self percept"},
}
_ENVELOPE = {"type": "object", "properties": {
    "v": {"type": "integer"}, "run": {"type": "string"}, "cycle": {"type": "integer"},
    "sender": {"type": "string"}, "sent_ns": {"type": "integer"}}}


def json_schema(kind: str) -> dict[str, Any]:
    """The JSON Schema of a kind's records (Foxglove reads it to offer the fields)."""
    cls = MESSAGE_TYPES.get(kind)
    if cls is None:
        raise CodecError(f"<schema {kind}>",
                         f"unknown message kind; known: {sorted(MESSAGE_TYPES)}")
    names = [n for n in cls.__dataclass_fields__ if n != "env"] + list(DERIVED.get(kind, ()))
    props = {"kind": {"type": "string", "const": kind}, "env": _ENVELOPE}
    props.update({n: _FIELDS.get(n, {}) for n in names})
    return {"$schema": "http://json-schema.org/draft-07/schema#", "title": f"teleo.{kind}",
            "type": "object", "properties": props, "required": ["kind", "env"]}
