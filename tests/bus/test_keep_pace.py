"""The lockstep world keeps pace with the launch's recorder (Clock.keep_pace), on a real bus
with the recorder standing in as a separate process that reports the cycles it holds when
told to: it waits until the recorder has the cycle asked for, not at all when there is no
recorder or it has gone, gives up on one that stopped moving (until it moves again), and a
stop interrupts it. Without the wait a run that outran its record lost the record's end when
its processes stopped (tests/e2e/test_record_drain.py)."""

from __future__ import annotations

import subprocess
import threading
from collections.abc import Iterator

import pytest
from bus_helpers import python

from bus import keys
from bus.clock import Clock, CycleInterrupted
from bus.config import BusConfig
from bus.errors import PaceLost
from bus.node import open_node
from tools.launching.supervisor import wait_until

RECORDER = """
import sys
from bus import keys
from bus.config import BusConfig
from bus.messages import ProcessStats
from bus.node import open_node

run, endpoint = sys.argv[1], sys.argv[2]
with open_node(BusConfig(connect=(endpoint,)), run, keys.RECORDER) as node:
    key = keys.stats(run, keys.RECORDER)
    node.declare([key])
    states = node.subscribe(keys.world_state(run))
    node.announce()
    print("up", flush=True)
    import threading
    def hear():
        while True:
            msg = states.get(None)
            print("state", msg.env.cycle, flush=True)
    threading.Thread(target=hear, daemon=True).start()
    for line in sys.stdin:            # a cycle to report, or "quit"
        if line.strip() == "quit":
            break
        node.publish(key, ProcessStats(node.envelope(int(line)), keys.RECORDER, 0.0, 0))
"""


class Recorder:
    def __init__(self, cfg: BusConfig, run: str) -> None:
        self.proc = python("-c", RECORDER, run, cfg.connect[0], stdin=subprocess.PIPE,
                           stdout=subprocess.PIPE, text=True)
        assert self.proc.stdout.readline().strip() == "up"

    def has(self, cycle: int) -> None:
        self.proc.stdin.write(f"{cycle}\n")
        self.proc.stdin.flush()

    def quit(self) -> None:
        if self.proc.poll() is None:
            self.proc.stdin.write("quit\n")
            self.proc.stdin.flush()
        self.proc.wait(30)


@pytest.fixture
def clock(cfg: BusConfig, run_id: str) -> Iterator[Clock]:
    with open_node(cfg, run_id, "world") as node:
        yield Clock(node, {}, stop=threading.Event())


@pytest.fixture
def recorder(cfg: BusConfig, run_id: str, clock: Clock) -> Iterator[Recorder]:
    rec = Recorder(cfg, run_id)
    assert clock.node.presence.wait_for(lambda alive: keys.RECORDER in alive, 30)
    yield rec
    rec.quit()


def pace_in_thread(clock: Clock, cycle: int, **kw: object) -> tuple[threading.Thread, list]:
    got: list = []

    def run() -> None:
        try:
            got.append(clock.keep_pace(keys.RECORDER, cycle, **kw))
        except (CycleInterrupted, PaceLost) as exc:
            got.append(exc)

    thread = threading.Thread(target=run)
    thread.start()
    return thread, got


def reported(clock: Clock, cycle: int) -> bool:
    return clock.last_seen.get(keys.RECORDER, -1) >= cycle


def test_it_waits_until_the_recorder_has_the_cycle(clock, recorder) -> None:
    thread, got = pace_in_thread(clock, 5)
    recorder.has(3)
    assert wait_until(lambda: reported(clock, 3), 30)
    assert thread.is_alive() and got == []      # 3 is not 5: still waiting
    recorder.has(6)
    thread.join(30)
    assert not thread.is_alive() and got[0] > 0.0
    assert clock.keep_pace(keys.RECORDER, 6) == 0.0  # already there


def test_no_recorder_or_one_gone_is_not_waited_for(clock, cfg, run_id) -> None:
    assert clock.keep_pace(keys.RECORDER, 100) == 0.0  # --no-record: nobody to wait for
    rec = Recorder(cfg, run_id)
    assert clock.node.presence.wait_for(lambda alive: keys.RECORDER in alive, 30)
    thread, got = pace_in_thread(clock, 100)
    rec.quit()                                         # it dies: the run goes on
    thread.join(30)
    assert not thread.is_alive() and isinstance(got[0], float)


def test_a_recorder_that_stopped_moving_is_given_up_until_it_moves(clock, recorder) -> None:
    recorder.has(2)
    clock.keep_pace(keys.RECORDER, 2)                  # back once it has cycle 2
    assert clock.keep_pace(keys.RECORDER, 10, stuck_s=0.3) >= 0.3
    assert clock.keep_pace(keys.RECORDER, 11, stuck_s=0.3) == 0.0  # given up: no wait
    recorder.has(4)                                    # it moves again: waited for again
    assert wait_until(lambda: clock.keep_pace(keys.RECORDER, 4) == 0.0
                      and reported(clock, 4), 30)
    thread, got = pace_in_thread(clock, 8)
    recorder.has(8)
    thread.join(30)
    assert not thread.is_alive() and isinstance(got[0], float)


def test_a_stop_interrupts_the_wait(clock, recorder) -> None:
    thread, got = pace_in_thread(clock, 50)
    clock.stop.set()
    thread.join(30)
    assert isinstance(got[0], CycleInterrupted)


def test_a_first_cycle_the_recorder_missed_is_sent_again_until_it_has_it(clock,
                                                                          recorder) -> None:
    """A recorder starved of CPU as the run starts can miss the first world state: the world
    holds the second cycle and sends the first again each second until the recorder has it
    (it reports -1: it has begun)."""
    from bus.messages import WorldState

    first = WorldState(clock.node.envelope(0), {"time": 0.0}, {}, [])
    thread, got = pace_in_thread(clock, -1, resend=first)
    heard = [recorder.proc.stdout.readline().split() for _ in range(2)]
    assert heard == [["state", "0"], ["state", "0"]]   # sent again, and again
    assert thread.is_alive()
    recorder.has(-1)
    thread.join(30)
    assert not thread.is_alive() and got[0] >= clock.resend_s


def test_a_required_recorder_that_left_stops_the_run_rather_than_lose_its_cycles(
        clock, cfg, run_id) -> None:
    """Drills 2026-12-04 D9: the world ran on when the recorder left its view, and the run
    ended "completed" with 64,734 of 65,712 cycles missing from its record."""
    rec = Recorder(cfg, run_id)
    assert clock.node.presence.wait_for(lambda alive: keys.RECORDER in alive, 30)
    rec.has(3)
    clock.keep_pace(keys.RECORDER, 3)                  # back once it has cycle 3
    thread, got = pace_in_thread(clock, 10, required_s=1.0)
    rec.quit()
    thread.join(60)
    assert isinstance(got[0], PaceLost) and "left the bus at cycle 10" in str(got[0])


def test_a_required_recorder_that_stopped_moving_holds_the_world_then_stops_it(
        clock, recorder) -> None:
    recorder.has(2)
    clock.keep_pace(keys.RECORDER, 2)
    thread, got = pace_in_thread(clock, 10, stuck_s=0.1, required_s=1.0)
    thread.join(0.5)
    assert thread.is_alive()              # held back past stuck_s: it is required
    thread.join(60)
    assert isinstance(got[0], PaceLost) and "has not moved from cycle 2" in str(got[0])


def test_a_required_recorder_that_catches_up_lets_the_world_on(clock, recorder) -> None:
    thread, got = pace_in_thread(clock, 5, required_s=30.0)
    recorder.has(5)
    thread.join(30)
    assert not thread.is_alive() and isinstance(got[0], float)
