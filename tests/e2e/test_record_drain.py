"""The launch's recorder when the run has outrun it (issue 24, item 7; trial #7: a `teleo stop`
of 19 s that said nothing): three publisher processes on a real bus send world states far
faster than the recorder writes them, so thousands wait in its queue when it is stopped. It
writes every one sent before its stop, saying about once a second how far it has got; cut
short (a second Ctrl-C) it stops at once and still closes the record whole, saying so.

The publishers keep their sessions open until the recorder has stopped: one that closes
while what it sent still waits in its queue for the recorder drops it (7,447 of 120,000 here
when they closed at once), which is why a lockstep world never runs far ahead of its record
(bus/clock.py Clock.keep_pace, tests/bus/test_keep_pace.py)."""

from __future__ import annotations

import subprocess
import sys
import uuid
from collections.abc import Iterator
from contextlib import contextmanager

import pytest

from bus.config import BusConfig
from bus.router import spawn_router
from tools.records.record_coverage import coverage
from tools.records.recorder import BusRecorder
from tools.records.run_record import RECORD_FILE, RunRecord

PUBLISHER = """
import sys
from bus import keys
from bus.config import BusConfig
from bus.messages import WorldState
from bus.node import open_node

run, endpoint, first, count = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
with open_node(BusConfig(connect=(endpoint,)), run, f"world{first}") as node:
    key = keys.world_state(run)
    node.declare([key])
    assert not node.wait_matching([key], 30), "no subscriber"
    snap = {"time": 0.0, "cars": [{"id": f"C{i}", "x": 1.5 * i, "y": 2.5, "speed": 3.25}
                                  for i in range(12)]}
    for cycle in range(first, first + count):
        snap["time"] = cycle * 0.1
        node.publish(key, WorldState(node.envelope(cycle), snap, {}, []))
    print("sent", flush=True)
    sys.stdin.read()   # until the test has stopped its recorder
"""
PUBLISHERS = 3


@pytest.fixture(scope="module")
def router() -> Iterator[str]:
    with spawn_router() as r:
        yield r.endpoint


@contextmanager
def outrun(router: str, tmp_path, each: int) -> Iterator[BusRecorder]:
    """A recorder of a new run, and PUBLISHERS processes that have each sent `each` world
    states (cycles 0 to PUBLISHERS * each - 1) to it, most of them still queued; they
    close when the block ends."""
    run = "t" + uuid.uuid4().hex[:8]
    recorder = BusRecorder(BusConfig(connect=(router,)), run, tmp_path / RECORD_FILE).start()
    publishers = [subprocess.Popen([sys.executable, "-c", PUBLISHER, run, router,
                                    str(k * each), str(each)], stdin=subprocess.PIPE,
                                   stdout=subprocess.PIPE, text=True)
                  for k in range(PUBLISHERS)]
    try:
        assert [p.stdout.readline().strip() for p in publishers] == ["sent"] * PUBLISHERS
        yield recorder
    finally:
        for p in publishers:
            p.stdin.close()
        assert [p.wait(60) for p in publishers] == [0] * PUBLISHERS


def test_a_long_drain_writes_everything_sent_before_the_stop_and_says_how_far(router,
                                                                             tmp_path):
    each = 40_000   # more than its queue holds (65536): the publishers waited for it
    said: list[tuple[float, int | None]] = []
    with outrun(router, tmp_path, each) as recorder:
        recorder.stop(progress=lambda r, seconds: said.append((seconds, r.last_cycle)))
    assert recorder.cycles == PUBLISHERS * each and recorder.report()["cut_short"] is False
    assert said, "a drain of a full queue took less than a second"
    assert [s for s, _ in said] == sorted(s for s, _ in said)
    assert all(c is not None and c < PUBLISHERS * each for _, c in said)
    record = RunRecord(tmp_path / RECORD_FILE)
    assert record.meta["teleo.recorder"]["cut_short"] == "false"
    assert coverage(tmp_path, PUBLISHERS * each)["gaps"] == []


def test_a_drain_cut_short_stops_at_once_with_a_whole_record_that_says_what_it_lacks(
        router, tmp_path):
    each = 20_000
    said: list[float] = []

    def cut(r: BusRecorder, seconds: float) -> None:
        said.append(seconds)
        r.cut_short()   # what a second Ctrl-C does (tools/launching/run_stop.py)

    with outrun(router, tmp_path, each) as recorder:
        recorder.stop(progress=cut)
    assert len(said) == 1 and recorder.report()["cut_short"] is True
    record = RunRecord(tmp_path / RECORD_FILE)   # closed whole: its index and metadata
    assert record.meta["teleo.recorder"]["cut_short"] == "true"
    held = int(record.meta["teleo.run"]["world_states"])
    assert 0 < held < PUBLISHERS * each
    assert coverage(tmp_path, PUBLISHERS * each)["missing"] == PUBLISHERS * each - held
