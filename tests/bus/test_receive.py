"""Receivers survive bad input from another process; queries answer or say who is missing."""

from __future__ import annotations

import pytest
from bus_helpers import python

from bus import keys
from bus.errors import NobodyServing, QueryFailed
from bus.messages import GoalReply, GoalRequest, Percepts
from bus.node import open_node


def test_garbage_is_counted_and_skipped_and_queries_survive_errors(cfg, run_id):
    goals = keys.goals(run_id, "A")
    with open_node(cfg, run_id, "test") as node:
        inbox = node.subscribe(keys.percepts(run_id, "A"))
        with pytest.raises(NobodyServing, match="nobody is serving"):
            node.query(goals, GoalRequest(node.envelope(), "list", "A"), timeout=0.5)
        peer = python("tests/bus/junk_peer.py", "--run", run_id, *cfg.to_args())
        try:
            assert node.presence.wait_for(lambda alive: "junk" in alive, 30)
            got = inbox.get(timeout=30)
            assert isinstance(got, Percepts) and got.env.cycle == 9
            assert inbox.dropped == 5 and inbox.received == 1

            reply = node.query(goals, GoalRequest(node.envelope(), "post", "A", "(g)"), 5)
            assert reply == GoalReply(reply.env, True, "post (g)", ({"id": "g1"},))
            with pytest.raises(QueryFailed, match="cannot cancel g7"):
                node.query(goals, GoalRequest(node.envelope(), "cancel", "A", goal_id="g7"), 5)
            raw = list(node.session.get(goals, payload=b"\x00junk", timeout=5))
            assert [r.err is not None for r in raw] == [True]
            assert node.query(goals, GoalRequest(node.envelope(), "list", "A"), 5).ok
            assert peer.poll() is None
        finally:
            peer.terminate()
            peer.wait(10)
    assert peer.returncode == 0
