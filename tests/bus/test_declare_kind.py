"""A message kind declared once (bus/kinds.py), here in the test and nowhere else, is encoded
with its rows packed, checked on decode with errors naming the key and field, matched to its
keys, recorded with its derived field and JSON Schema, written to a run record and replayed
from it; and a declaration against the rules is refused naming the class."""

from __future__ import annotations

import msgpack
import pytest

from bus import keys
from bus.codec import decode, encode
from bus.errors import CodecError
from bus.fields import NAME, Rows
from bus.kinds import DeclarationError, Derived, MessageKind, message, spec
from bus.messages import Actions, Envelope
from bus.record import derived, from_record, json_schema, message_record, to_record
from bus.schema import Int
from tools.records.run_record import RecordWriter, RunRecord


@message
class Heartbeat(MessageKind):
    """A test kind: an agent's beats, with rows."""

    KIND = "TestHeartbeat"
    KEYS = ("agent/*/heartbeat",)
    PACKED = "rows"
    DERIVED = {"count": Derived(lambda body: len(body.get("rows") or ()),
                                {"type": "integer"})}
    env: Envelope
    agent: str = spec(NAME)
    rows: tuple = spec(Rows())
    beats: int = spec(Int(0), default=0)


ENV = Envelope(1, "r1", 3, "test", 99)
KEY = "teleo/r1/agent/ME/heartbeat"
BEAT = Heartbeat(ENV, "ME", (["pulse", 1.5], ["pulse", 2]), 7)


def test_its_key_allows_it_and_only_it() -> None:
    assert keys.kind_of_key(KEY) == {"TestHeartbeat"}
    assert keys.kind_of_key(keys.actions("r1", "ME")) == {"Actions"}
    with pytest.raises(CodecError, match="wrong message kind 'TestHeartbeat'"):
        decode(keys.actions("r1", "ME"), encode(BEAT))
    with pytest.raises(CodecError, match="wrong message kind 'Actions'"):
        decode(KEY, encode(Actions(ENV, "ME", ())))


def test_it_round_trips_with_its_rows_packed_and_its_defaults() -> None:
    wire = msgpack.unpackb(encode(BEAT), raw=False)
    assert wire["kind"] == "TestHeartbeat" and all(type(r) is bytes for r in wire["rows"])
    assert decode(KEY, encode(BEAT)) == BEAT
    del wire["beats"]
    assert decode(KEY, msgpack.packb(wire, use_bin_type=True)).beats == 0


@pytest.mark.parametrize(("field", "value", "problem"), [
    ("beats", -1, "TestHeartbeat.beats: expected an integer in [0, 18446744073709551615], got -1"),
    ("agent", [], "TestHeartbeat.agent: expected a name, got []"),
    ("rows", [["pulse", None]], "TestHeartbeat.rows"),
])
def test_a_bad_field_is_refused_naming_the_key_and_field(field, value, problem) -> None:
    wire = msgpack.unpackb(encode(BEAT), raw=False)
    wire[field] = value
    with pytest.raises(CodecError) as caught:
        decode(KEY, msgpack.packb(wire, use_bin_type=True))
    assert str(caught.value).startswith(f"{KEY}: {problem}")


def test_it_is_recorded_and_replayed_from_a_run_record(tmp_path) -> None:
    record = message_record(KEY, BEAT)
    assert record["count"] == 2 and record["rows"] == [["pulse", 1.5], ["pulse", 2]]
    assert derived("TestHeartbeat") == ("count",)
    assert set(json_schema("TestHeartbeat")["properties"]) == \
        {"kind", "env", "agent", "rows", "beats", "count"}
    path = tmp_path / "run.mcap"
    with RecordWriter(path, "r1") as writer:
        writer.add(KEY, record)
        writer.add(keys.world_state("r1"), {"kind": "WorldState", "env": {**record["env"]},
                                            "snapshot": {"time": 0.3}, "outcomes": {},
                                            "events": []})
    read = dict(RunRecord(path).records())
    assert read[KEY] == record
    assert decode(KEY, from_record(KEY, read[KEY])) == BEAT
    assert to_record(KEY, from_record(KEY, read[KEY])) == record


def test_a_declaration_against_the_rules_is_refused_naming_the_class() -> None:
    with pytest.raises(DeclarationError, match="Unchecked.note: expected a field declared "
                                               "with spec"):
        @message
        class Unchecked(MessageKind):
            KIND = "TestUnchecked"
            env: Envelope
            note: str = ""
    with pytest.raises(DeclarationError, match="'Actions' is already"):
        @message
        class Other(MessageKind):
            KIND = "Actions"
            env: Envelope
