"""FifoInbox on a real bus: a publisher in another process sends thousands of messages while
the reader is away; they wait in zenoh's own FIFO (no Python on zenoh's thread per sample)
and come out of `drain`, in batches, every one, in order (the run record relies on it)."""

from __future__ import annotations

import time

from bus_helpers import python

from bus import keys
from bus.codec import decode
from bus.node import open_node

COUNT = 5000
PUBLISHER = """
import sys, time
from bus import keys
from bus.config import BusConfig
from bus.messages import Envelope, Percepts
from bus.node import open_node

run, endpoint, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
cfg = BusConfig(mode="client", connect=(endpoint,), listen=())
with open_node(cfg, run, "pub") as node:
    key = keys.percepts(run, "ME")
    node.declare([key])
    assert not node.wait_matching([key], 30), "no subscriber"
    for cycle in range(count):
        rows = tuple(["car", f"C{i}", float(cycle), 2.5] for i in range(10))
        node.publish(key, Percepts(node.envelope(cycle), "ME", rows))
        if cycle % 100 == 99:
            time.sleep(0.005)  # bursts of 100: what a run of many agents sends at once
"""


def test_a_fifo_inbox_keeps_every_sample_while_its_reader_is_away(cfg, run_id) -> None:
    with open_node(cfg, run_id, "reader") as node:
        inbox = node.subscribe_fifo(keys.run_all(run_id))
        publisher = python("-c", PUBLISHER, run_id, cfg.connect[0], str(COUNT))
        assert publisher.wait(120) == 0                  # all sent, none read yet
        got: list[tuple[str, bytes]] = []
        deadline = time.monotonic() + 30
        while len(got) < COUNT and time.monotonic() < deadline:
            batch = inbox.drain(most=1000)
            assert len(batch) <= 1000
            got += batch
            if not batch:
                time.sleep(0.01)
        assert inbox.drain() == []
    assert len(got) == COUNT
    assert {key for key, _ in got} == {keys.percepts(run_id, "ME")}
    cycles = [decode(key, payload).env.cycle for key, payload in got]
    assert cycles == list(range(COUNT))
