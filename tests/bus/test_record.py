"""The recorded form of bus messages (bus/record.py): every kind goes to JSON and back to the
same message, Percepts gain the derived `self`, schemas describe every field, and a bad
payload or record is refused with an error naming the key."""

from __future__ import annotations

import json

import pytest

from bus import keys
from bus.codec import decode, encode
from bus.errors import CodecError
from bus.messages import (
    Actions,
    Beliefs,
    Envelope,
    GoalList,
    Intention,
    Percepts,
    ProcessStats,
    WorldEvent,
    WorldState,
)
from bus.record import derived, from_record, json_schema, message_record, to_record

ENV = Envelope(1, "r1", 7, "test", 123)
MESSAGES = [
    (keys.world_state("r1"), WorldState(ENV, {"time": 0.7, "cars": [{"id": "ME"}]},
                                        {"ME": [{"action": ["*gas", 5], "status": "done",
                                                 "reason": ""}]}, [])),
    (keys.percepts("r1", "ME"), Percepts(ENV, "ME", (["street", "B"], ["self", "ME", "speed",
                                                     7.5, "segment", "S1"]))),
    (keys.beliefs("r1", "ME"), Beliefs(ENV, "ME", (["at-street", "ME", "B"],))),
    (keys.actions("r1", "ME"), Actions(ENV, "ME", (["*gas", 6.25],))),
    (keys.intention("r1", "ME"), Intention(ENV, "ME", {"cycle": 7, "goals": [], "why": []})),
    (keys.goal_list("r1", "ME"), GoalList(ENV, "ME", ({"id": "g1", "goal": "(x)",
                                                       "priority": 5, "status": "active"},))),
    (keys.stats("r1", "ME.inference"), ProcessStats(ENV, "ME.inference", 0.5, 0)),
    (keys.world_events("r1"), WorldEvent(ENV, {"kind": "block", "segment": "S3"})),
]


@pytest.mark.parametrize(("key", "msg"), MESSAGES, ids=[m.KIND for _, m in MESSAGES])
def test_a_message_goes_to_json_and_back_unchanged(key, msg) -> None:
    record = json.loads(json.dumps(message_record(key, msg)))  # what the MCAP file holds
    assert record["kind"] == msg.KIND and record["env"]["cycle"] == 7
    assert decode(key, from_record(key, record)) == decode(key, encode(msg))


def test_percepts_carry_the_agents_own_self_percept_as_an_object() -> None:
    key, msg = MESSAGES[1]
    assert message_record(key, msg)["self"] == {"speed": 7.5, "segment": "S1"}
    others = Percepts(ENV, "ME", (["self", "YOU", "speed", 1.0],))
    assert message_record(key, others)["self"] == {}
    assert derived("Percepts") == ("self",) and derived("Beliefs") == ()


def test_every_kind_has_a_schema_naming_its_fields() -> None:
    for _, msg in MESSAGES:
        schema = json_schema(msg.KIND)
        record = message_record("k", msg) if msg.KIND != "WorldState" else \
            message_record(keys.world_state("r1"), msg)
        assert schema["title"] == f"teleo.{msg.KIND}"
        assert set(record) <= set(schema["properties"]), msg.KIND
    with pytest.raises(CodecError, match="unknown message kind"):
        json_schema("Nonsense")


def test_bad_payloads_and_records_are_refused_naming_the_key() -> None:
    key = keys.percepts("r1", "ME")
    with pytest.raises(CodecError, match=key):
        to_record(key, b"\xc1 not msgpack")
    with pytest.raises(CodecError, match="not a bus message"):
        to_record(key, encode(MESSAGES[3][1])[:0] + b"\x90")  # an empty msgpack array
    record = message_record(key, MESSAGES[1][1])
    record["percepts"] = [["self", "ME", "speed", None]]
    with pytest.raises(CodecError, match=f"{key}.*Percepts.percepts"):
        from_record(key, record)
