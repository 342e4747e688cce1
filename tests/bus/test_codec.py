"""Codec: every message kind round-trips; anything malformed raises CodecError naming the key."""

from __future__ import annotations

import msgpack
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bus import keys
from bus.codec import decode, encode
from bus.errors import CodecError
from bus.messages import (
    GOAL_OPS,
    Actions,
    Beliefs,
    Envelope,
    GoalList,
    GoalReply,
    GoalRequest,
    Intention,
    Percepts,
    ProcessStats,
    WorldEvent,
    WorldState,
    WorldStatic,
)

text = st.text(max_size=12)
ints = st.integers(min_value=-(2**63), max_value=2**63 - 1)
finite = st.floats(allow_nan=False, allow_infinity=False)
atoms = st.one_of(text, ints, finite)   # rows hold finite numbers only
rows = st.lists(st.tuples(text, st.lists(atoms, max_size=7)).map(lambda r: [r[0], *r[1]]),
                max_size=10).map(tuple)   # [name, value, ...]
plain = st.recursive(   # plain data: what a map-valued field may hold (bus/fields.py)
    st.one_of(st.none(), st.booleans(), ints, finite, text),
    lambda inner: st.one_of(st.lists(inner, max_size=4),
                            st.dictionaries(text, inner, max_size=4)),
    max_leaves=12)
maps = st.dictionaries(text, plain, max_size=5)
outcomes = st.lists(st.fixed_dictionaries({
    "action": st.lists(atoms, min_size=1, max_size=3),
    "status": st.sampled_from(["done", "failed"]), "reason": text}), max_size=3)
envs = st.builds(Envelope, v=st.just(1), run=text, cycle=st.integers(-1, 2**40),
                 sender=text, sent_ns=st.integers(0, 2**63 - 1))

MESSAGES = {
    "world_state": (lambda: keys.world_state("r"), st.builds(
        WorldState, envs, maps, st.dictionaries(text, outcomes, max_size=3),
        st.lists(maps, max_size=3))),
    "world_static": (lambda: keys.world_static("r"), st.builds(  # issue 35
        WorldStatic, envs, st.sampled_from(["driving", "blocks", "office"]), maps)),
    "percepts": (lambda: keys.percepts("r", "ME"), st.builds(Percepts, envs, text, rows)),
    "beliefs": (lambda: keys.beliefs("r", "ME"), st.builds(Beliefs, envs, text, rows)),
    "actions": (lambda: keys.actions("r", "ME"), st.builds(Actions, envs, text, rows)),
    "intention": (lambda: keys.intention("r", "ME"), st.builds(Intention, envs, text, maps)),
    "goal_request": (lambda: keys.goals("r", "ME"), st.builds(
        GoalRequest, envs, st.sampled_from(GOAL_OPS), text, text, ints, text)),
    "goal_reply": (lambda: keys.goals("r", "ME"), st.builds(
        GoalReply, envs, st.booleans(), text, st.lists(maps, max_size=3).map(tuple))),
    "goal_list": (lambda: keys.goal_list("r", "ME"), st.builds(
        GoalList, envs, text, st.lists(st.fixed_dictionaries(
            {"id": st.text(min_size=1, max_size=12), "goal": text, "priority": ints,
             "status": text}), max_size=3)
        .map(tuple))),
    "stats": (lambda: keys.stats("r", "ME.inference"), st.builds(
        ProcessStats, envs, text, st.floats(0, 1e9), st.integers(0, 2**63 - 1))),
    "event": (lambda: keys.world_events("r"), st.builds(WorldEvent, envs, maps)),
}


@pytest.mark.parametrize("kind", sorted(MESSAGES))
def test_every_kind_round_trips(kind):
    key_fn, strategy = MESSAGES[kind]

    @settings(max_examples=25, deadline=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
    @given(strategy)
    def round_trip(msg):
        assert decode(key_fn(), encode(msg)) == msg

    round_trip()


@pytest.mark.parametrize("kind", sorted(MESSAGES))
def test_every_kind_carries_the_major_version_and_is_refused_under_another(kind):
    """docs/bus.md, "Envelope and protocol version": every message's env.v is the major
    version, an int, and the same message under major version 2 is refused naming both."""
    key_fn, strategy = MESSAGES[kind]

    @settings(max_examples=5, deadline=None,
              suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
    @given(strategy)
    def carries(msg):
        raw = msgpack.unpackb(encode(msg))
        assert type(raw["env"]["v"]) is int and raw["env"]["v"] == 1
        raw["env"]["v"] = 2
        with pytest.raises(CodecError, match="unknown schema version 2: this reader speaks "
                                             "major version 1 only"):
            decode(key_fn(), msgpack.packb(raw))

    carries()


ENV = Envelope(1, "r", 3, "ME.perception", 123)
KEY = keys.percepts("r", "ME")


def body(**changes):
    base = {"kind": "Percepts", "env": {"v": 1, "run": "r", "cycle": 3, "sender": "x",
                                        "sent_ns": 1}, "agent": "ME", "percepts": [["a", 1]]}
    base.update(changes)
    return msgpack.packb(base)


@pytest.mark.parametrize("payload, problem", [
    (b"\xc1garbage", "malformed msgpack"),
    (b"", "malformed msgpack"),
    (msgpack.packb([1, 2]), "expected a msgpack map"),
    (msgpack.packb({1: 2}), "malformed msgpack"),
    (body(env={"v": 2, "run": "r", "cycle": 3, "sender": "x", "sent_ns": 1}),
     "unknown schema version 2"),
    (body(kind="Nope"), "unknown message kind"),
    (body(kind="Beliefs", beliefs=[]), "wrong message kind 'Beliefs'"),
    (body(percepts=[["a", True]]), "Percepts.percepts"),
    (body(percepts=[["a", None]]), "Percepts.percepts"),
    (body(percepts=[["a", 1], ["b", 2.5], ["c", b"bytes"]]), "found item"),
    (body(percepts=[["a", 1], ["b", ["nested"]]]), "found item"),
    (body(percepts=[["a", 1], {"b": 2}]), "found item"),
    (body(percepts=[["a", 1], "b"]), "found item"),
    (body(percepts="abc"), "expected array"),
    (body(agent=7), "Percepts.agent: expected a name, got 7"),
    (body(env={"v": 1, "run": "r"}), "malformed envelope"),
])
def test_bad_payloads_raise_codec_error_naming_the_key(payload, problem):
    with pytest.raises(CodecError, match=problem) as err:
        decode(KEY, payload)
    assert err.value.key == KEY
    assert str(err.value).startswith(KEY)


@pytest.mark.parametrize("kind, key, field", [
    ("Percepts", keys.percepts("r", "ME"), "percepts"),
    ("Beliefs", keys.beliefs("r", "ME"), "beliefs"),
    ("Actions", keys.actions("r", "ME"), "actions"),
])
@pytest.mark.parametrize("bad", [float("nan"), float("inf"), float("-inf")])
def test_non_finite_numbers_in_rows_are_refused_naming_the_key(kind, key, field, bad):
    raw = msgpack.unpackb(body())
    del raw["percepts"]
    raw.update(kind=kind, **{field: [["speed", "ME", 1.5], ["speed", "ME", bad]]})
    with pytest.raises(CodecError, match=f"{kind}.{field}: expected finite numbers, found") \
            as err:
        decode(key, msgpack.packb(raw))
    assert str(err.value).startswith(key)


def test_missing_field_is_an_error_and_unknown_fields_are_ignored():
    raw = msgpack.unpackb(body())
    del raw["agent"]
    with pytest.raises(CodecError, match="lacks field 'agent'"):
        decode(KEY, msgpack.packb(raw))
    msg = decode(KEY, body(added_in_v1_1="ignored"))
    assert msg == Percepts(Envelope(1, "r", 3, "x", 1), "ME", (["a", 1],))


def test_goal_request_op_is_checked_and_defaults_apply():
    raw = msgpack.unpackb(encode(GoalRequest(ENV, "list", "ME")))
    assert decode(keys.goals("r", "ME"), msgpack.packb(raw)) == GoalRequest(ENV, "list", "ME")
    raw["op"] = "explode"
    with pytest.raises(CodecError, match="GoalRequest.op: expected a goal operation, one of "
                                         "'post', .*, got 'explode'"):
        decode(keys.goals("r", "ME"), msgpack.packb(raw))


def test_unencodable_message_is_a_codec_error():
    with pytest.raises(CodecError, match="not msgpack-able"):
        encode(Intention(ENV, "ME", {"x": object()}))


def test_encode_works_after_a_failed_encode_and_big_rows_round_trip():
    with pytest.raises(CodecError):
        encode(Intention(ENV, "ME", {"x": object()}))
    rows = tuple(["lane-line", f"L{i}", "dist", 1.5 + i, "angle", i, "ok"] for i in range(300))
    msg = Percepts(ENV, "ME", rows)
    assert encode(msg) == msgpack.packb(msgpack.unpackb(encode(msg)), use_bin_type=True)
    assert decode(KEY, encode(msg)) == msg


def test_subclasses_are_not_bus_messages():
    class MyPercepts(Percepts):
        pass

    with pytest.raises(CodecError, match="not a bus message"):
        encode(MyPercepts(ENV, "ME", ()))


WHOLE = ("malformed msgpack", "expected a msgpack map", "unknown schema version",
         "unknown message kind", "wrong message kind", "malformed envelope", "lacks field")


@pytest.mark.parametrize("kind", sorted(MESSAGES))
def test_any_spoilt_field_is_decoded_as_valid_or_refused_naming_kind_and_field(kind):
    """Issue 24, item 1: a valid message with fields replaced by junk of any type (deep,
    huge, NaN, bytes, unhashable) is either still valid, and then re-encodes, or refused
    with a CodecError naming the key and `Kind.field` (or the payload as a whole)."""
    import sys
    from pathlib import Path

    sys.path.append(str(Path(__file__).resolve().parents[2] / "bench" / "faults"))
    from fuzz_values import mutate, wire

    key_fn, strategy = MESSAGES[kind]

    @settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
    @given(strategy, st.randoms(use_true_random=False))
    def prop(msg, rng):
        body = mutate(msgpack.unpackb(encode(msg)), rng)
        data = wire(body)
        if data is None:
            return
        try:
            got = decode(key_fn(), data)
        except CodecError as exc:
            text = str(exc)
            assert text.startswith(key_fn() + ": ")
            assert any(w in text for w in WHOLE) or f"{msg.KIND}." in text, text
        else:
            decode(key_fn(), encode(got))   # what is accepted can be sent on

    prop()


def test_every_message_carries_the_major_version_and_another_major_is_refused_naming_both():
    sent = encode(Percepts(Envelope.now("r", 3, "x"), "ME", (("a", 1),)))
    raw = msgpack.unpackb(sent)
    assert raw["env"]["v"] == 1 and type(raw["env"]["v"]) is int
    raw["env"]["v"] = 2
    with pytest.raises(CodecError) as err:
        decode(KEY, msgpack.packb(raw))
    assert str(err.value) == (f"{KEY}: unknown schema version 2: this reader speaks major "
                              "version 1 only (a minor change only adds fields, which a reader "
                              "ignores, and keeps the version)")
    raw["env"]["v"] = "1.1"
    with pytest.raises(CodecError, match=r"unknown schema version '1.1': expected the major "
                                         r"version as an integer \(this reader's is 1\)"):
        decode(KEY, msgpack.packb(raw))


def test_a_minor_change_adding_fields_is_read_by_this_reader():
    raw = msgpack.unpackb(encode(Percepts(Envelope.now("r", 3, "x"), "ME", (("a", 1),))))
    raw["env"]["trace_id"] = "abc"   # new fields in the envelope and the body
    raw["confidence"] = 0.5
    got = decode(KEY, msgpack.packb(raw))
    assert got.agent == "ME" and got.env.v == 1 and got.env.cycle == 3
