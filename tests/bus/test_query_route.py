"""A query asked before its queryable is routed here (a tool started right after a router
restart, or just before the serving process is up) waits for it within its timeout instead
of failing at once: zenoh answers a get that no known queryable matches with no reply, at
once (the tests/e2e router-kill drill met this as soon as the tools started quicker)."""

from __future__ import annotations

import subprocess
import textwrap

import pytest
from bus_helpers import python

from bus import keys
from bus.errors import NobodyServing
from bus.messages import Envelope, EventReply, WorldEvent
from bus.node import open_node

SERVER = textwrap.dedent("""
    import sys, time
    from bus import keys
    from bus.config import BusConfig
    from bus.messages import Envelope, EventReply
    from bus.node import open_node
    run, endpoint = sys.argv[1], sys.argv[2]
    time.sleep(1.5)   # the query is already waiting
    with open_node(BusConfig(connect=(endpoint,)), run, "late-server") as node:
        node.serve(keys.world_events(run),
                   lambda req: EventReply(Envelope.now(run, -1, "late-server"), True, "late", {}))
        print("serving", flush=True)
        time.sleep(20)
""")


def test_a_query_waits_within_its_timeout_for_a_queryable_that_comes_late(cfg, run_id):
    server = python("-c", SERVER, run_id, cfg.connect[0], stdout=subprocess.PIPE, text=True)
    try:
        with open_node(cfg, run_id, "asker") as node:
            reply = node.query(keys.world_events(run_id),
                               WorldEvent(Envelope.now(run_id, -1, "asker"), {"kind": "x"}),
                               15.0)
        assert isinstance(reply, EventReply) and reply.ok and reply.reason == "late"
    finally:
        server.kill()
        server.wait(10)


def test_with_no_queryable_at_all_the_query_still_fails_naming_the_key(cfg, run_id):
    with open_node(cfg, run_id, "asker") as node, pytest.raises(NobodyServing) as info:
        node.query(keys.world_events(run_id), WorldEvent(Envelope.now(run_id, -1, "asker"),
                                                         {"kind": "x"}), 1.0)
    assert keys.world_events(run_id) in str(info.value)
