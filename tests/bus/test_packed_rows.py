"""Packed rows (bus/codec.py, docs/bus.md "Packed rows"): percepts and beliefs travel one
msgpack bin per row; a reader gives a row it saw in the last message on the same key, byte for
byte, as the very same list, so the engine reads only what changed."""

from __future__ import annotations

import msgpack
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bus import keys
from bus.codec import decode, encode
from bus.errors import CodecError
from bus.messages import Beliefs, Envelope, Percepts
from bus.record import from_record, to_record

KEY = keys.percepts("r1", "ME")


def percepts(rows, cycle=0, key_agent="ME") -> bytes:
    return encode(Percepts(Envelope(1, "r1", cycle, "ME.perception", 0), key_agent, tuple(rows)))


def test_each_row_travels_as_its_own_msgpack_bytes():
    body = msgpack.unpackb(percepts([["self", "ME", "speed", 2.5], ["man", "M1"]]))
    assert body["percepts"] == [msgpack.packb(["self", "ME", "speed", 2.5]),
                                msgpack.packb(["man", "M1"])]


def test_a_row_unchanged_since_the_last_message_is_the_same_list():
    first = decode(KEY, percepts([["self", "ME", "speed", 2.5], ["man", "M1", "dist", 3]], 0))
    second = decode(KEY, percepts([["self", "ME", "speed", 2.75], ["man", "M1", "dist", 3]], 1))
    assert second.percepts == (["self", "ME", "speed", 2.75], ["man", "M1", "dist", 3])
    assert second.percepts[1] is first.percepts[1]
    assert second.percepts[0] is not first.percepts[0]


@pytest.mark.parametrize("was, now", [(3, 3.0), (0.0, -0.0), (1, True)])
def test_equal_values_of_another_type_or_zero_sign_are_a_new_row(was, now):
    key = keys.percepts("r1", "A7")
    first = decode(key, percepts([["obj", "O", "v", was]], 0, "A7"))
    if isinstance(now, bool):  # a bool is no percept value: refused by name
        with pytest.raises(CodecError, match="A7/percepts"):
            decode(key, percepts([["obj", "O", "v", now]], 1, "A7"))
        return
    second = decode(key, percepts([["obj", "O", "v", now]], 1, "A7"))
    assert second.percepts[0] is not first.percepts[0]
    assert repr(second.percepts[0][3]) == repr(now)


def test_rows_are_shared_per_key_only():
    a = decode(keys.percepts("r1", "A"), percepts([["man", "M1"]], 0, "A"))
    b = decode(keys.percepts("r1", "B"), percepts([["man", "M1"]], 0, "B"))
    assert a.percepts[0] is not b.percepts[0]


def _raw(items, agent="ME") -> bytes:
    return msgpack.packb({"kind": "Percepts", "env": {"v": 1, "run": "r1", "cycle": 0,
                                                      "sender": "x", "sent_ns": 0},
                          "agent": agent, "percepts": items}, use_bin_type=True)


def test_plain_arrays_and_a_mix_are_read_as_well():
    msg = decode(KEY, _raw([["man", "M1"], msgpack.packb(["self", "ME"])]))
    assert msg.percepts == (["man", "M1"], ["self", "ME"])


@pytest.mark.parametrize("item, problem", [
    (b"\xc1", "malformed packed row"),
    (msgpack.packb(["a"]) + msgpack.packb(["b"]), "malformed packed row"),
    (msgpack.packb({"a": 1}), "expected arrays of str, int or float"),
    (msgpack.packb(["x", float("nan")]), "finite"),
    (msgpack.packb([]), "with a name first"),
    (msgpack.packb([3, "x"]), "with a name first"),
])
def test_a_bad_packed_row_is_refused_naming_the_key_and_field(item, problem):
    with pytest.raises(CodecError, match=f"Percepts.percepts.*{problem}") as err:
        decode(KEY, _raw([msgpack.packb(["man", "M1"]), item]))
    assert err.value.key == KEY


def test_a_record_holds_plain_rows_and_plays_back():
    payload = encode(Beliefs(Envelope(1, "r1", 3, "ME.inference", 0), "ME",
                             (["near", "B1"], ["clear", "B2"])))
    key = keys.beliefs("r1", "ME")
    record = to_record(key, payload)
    assert record["beliefs"] == [["near", "B1"], ["clear", "B2"]]
    assert decode(key, from_record(key, record)).beliefs == (["near", "B1"], ["clear", "B2"])


atoms = st.one_of(st.text(max_size=6), st.integers(-3, 3), st.sampled_from([0.0, -0.0, 1.0, 2.5]))
row = st.tuples(st.text(max_size=6), st.lists(atoms, max_size=4)).map(
    lambda r: [r[0], *r[1]])   # [name, value, ...]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.lists(row, max_size=6), min_size=1, max_size=6))
def test_messages_decode_to_what_was_sent_and_reuse_only_identical_rows(messages):
    key = keys.beliefs("r-hyp", "H")
    last: dict[bytes, list] = {}   # bytes -> every row of the last message with those bytes
    for cycle, rows in enumerate(messages):
        got = decode(key, encode(Beliefs(Envelope(1, "r-hyp", cycle, "s", 0), "H",
                                         tuple(rows)))).beliefs
        assert [list(map(repr, r)) for r in got] == [list(map(repr, r)) for r in rows]
        for r, g in zip(rows, got, strict=True):
            olds = last.get(msgpack.packb(r))   # a row sent twice may be either of them
            assert any(g is old for old in olds) if olds else True
        last = {}
        for r, g in zip(rows, got, strict=True):
            last.setdefault(msgpack.packb(r), []).append(g)


def test_rows_handed_over_in_memory_are_shared_as_a_receiver_would_get_them():
    from bus.rows import shared_rows

    first = shared_rows("Percepts", "K1", (["self", "K1", "speed", 2.5], ["man", "M1", "d", 3]))
    second = shared_rows("Percepts", "K1", (["self", "K1", "speed", 2.5], ["man", "M1", "d", 3.0]))
    assert second[0] is first[0] and second[1] is not first[1]
    assert repr(second[1][3]) == "3.0"
    env = Envelope(1, "r1", 1, "K1.perception", 0)
    # the message encodes as if nothing had been shared, and decodes to the same rows
    assert encode(Percepts(env, "K1", second)) == encode(Percepts(env, "K1", tuple(
        list(r) for r in second)))
    assert decode(keys.percepts("r1", "K1"), encode(Percepts(env, "K1", second))).percepts \
        == second


def test_plain_arrays_are_never_taken_for_last_messages_rows():
    key = keys.percepts("r1", "P9")
    first = decode(key, _raw([["obj", "O", "v", 3], ["man", "M1"]]))
    again = decode(key, _raw([["obj", "O", "v", 3.0], ["man", "M1"]]))  # equal to ==
    assert repr(again.percepts[0][3]) == "3.0"
    assert again.percepts[0] is not first.percepts[0]
