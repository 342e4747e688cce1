"""`Node.publish_many` leaves out, unencoded, a message on a key no subscriber matches (zenoh
would send it nowhere): a shared process's percepts and beliefs in a run without a record
cost no encoding. Once a subscriber matches, the same message is encoded and delivered."""

from __future__ import annotations

import time

import pytest

from bus import keys
from bus.errors import CodecError
from bus.messages import Actions, Percepts
from bus.node import open_node


def test_a_message_nobody_subscribes_to_is_not_encoded_and_one_matched_is(cfg, run_id):
    p_key, a_key = keys.percepts(run_id, "A"), keys.actions(run_id, "A")
    with open_node(cfg, run_id, "agents1") as node, open_node(cfg, run_id, "world") as world:
        actions = world.subscribe(a_key)
        node.declare([p_key, a_key])
        assert not node.wait_matching([a_key], 20)
        # an object msgpack cannot write: encoding it would raise
        bad = Percepts(node.envelope(0), "A", (), memory={"model": object()})
        node.publish_many([(p_key, bad), (a_key, Actions(node.envelope(0), "A", (["*pass"],)))])
        assert actions.get(timeout=10.0).actions == (["*pass"],)
        percepts = world.subscribe(p_key)
        assert not node.wait_matching([p_key], 20)
        with pytest.raises(CodecError, match="not msgpack-able"):
            node.publish_many([(p_key, bad)])
        good = Percepts(node.envelope(1), "A", (["self", "A"],))
        deadline = time.monotonic() + 10
        got = None
        while got is None and time.monotonic() < deadline:
            node.publish_many([(p_key, good)])
            got = percepts.get(timeout=0.5)
    assert got is not None and got.percepts == (["self", "A"],)
