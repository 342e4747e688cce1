"""Who writes run records off the bus: `BusRecorder` takes every message of a run (the launcher
starts one before any process, so cycle 0 is in; `teleo record` runs one in the foreground).
The launch's recorder and `teleo simulate`'s are made in tools/records/run_recorders.py.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from bus import keys
from bus.config import BusConfig
from bus.errors import BusError, CodecError
from bus.messages import (
    ProcessStats,
    WorldStatic,
)
from bus.node import FifoInbox, open_node
from bus.record import message_record, to_record
from tools.records.run_record import RecordWriter

log = logging.getLogger(__name__)
RECORDER_META = "teleo.recorder"
LOOK_S = 0.02  # [s] between looks at the subscription when nothing waits
FOREGROUND_SETTLE_S = 1.0  # [s] `teleo record`: messages still in flight taken after the stop
FOREGROUND_STOP_S = 10.0  # [s] `teleo record`: the longest it writes after its stop
PROGRESS_S = 0.05  # [s] a launch's recorder says the cycle it has reached at most this often
AGAIN_S = 0.5      # [s] and says it again this often when it has not moved
STATIC_ASK_S = 0.5  # [s] the wait for the world's answer about its static part:
                    # a live world answers in milliseconds; where none serves it (a launch's
                    # recorder starts before its world) the record is not held back long


class BusRecorder:
    """Records `teleo/<run>/**` into a RecordWriter on a thread of its own.

    `start()` returns once the subscription is declared; `stop()` records what was sent
    before it and no more (see there) and closes the record. The thread keeps the launcher's
    priority: when it ran at nice 10, on a loaded machine, the scheduler kept it waiting while
    it held the GIL, which stalled zenoh's callback thread (the record's inbox was then fed by
    a callback), and the router dropped what it held for the record (the last 64 cycles of
    8262 lost, and a stop of 16 s while the thread caught up).
    """

    def __init__(self, cfg: BusConfig, run: str, path: Path, meta: dict[str, str] | None = None,
                 process: str = "record") -> None:
        self.cfg, self.run, self.process = cfg, run, process
        self.writer = RecordWriter(path, run, meta)
        self.received = 0  # messages taken for the record (sent before the stop)
        self.dropped = 0  # of those, not recorded (not a bus message)
        self.after_stop = 0  # messages sent after the stop: left out
        self.first_cycle: int | None = None  # of the messages recorded (cycle >= 0)
        self.last_cycle: int | None = None
        self._cycles: set[int] = set()  # the distinct cycles of the messages recorded
        self.cpu_s = 0.0
        self._announce, self._quiet_s, self._settle_s = False, 0.3, None
        self._until: int | None = None  # stop(): the cycles the record must reach
        self._stop_ns: int | None = None  # wall clock of the stop [ns]: later sends left out
        self.error: BaseException | None = None
        self.failed: dict[str, Any] = {}  # the write that failed: {"cycle", "reason"}
        self._own = keys.stats(run, process)  # a launch's recorder says its progress there
        self._node = None  # the session it says it on (a launch's recorder only)
        self._told, self._told_at = -2, 0.0  # the cycle last said (-1: it has begun), when
        self.cut = False  # stop() left out what was still queued (its time was up, or asked)
        self._ready = threading.Event()
        self._stop = threading.Event()
        self._abandon = threading.Event()  # stop() waited long enough: write nothing more
        self._thread = threading.Thread(target=self._main, name="teleo-record", daemon=True)

    @property
    def cycles(self) -> int:
        """How many distinct cycles the recorded messages belong to."""
        return len(self._cycles)

    def start(self, timeout: float = 30.0, announce: bool = False) -> BusRecorder:
        """Subscribe (and, with `announce`, declare the liveliness token `process` after it)."""
        self._announce = announce
        self._thread.start()
        if not self._ready.wait(timeout) or self.error is not None:
            raise BusError(f"recorder of run {self.run}: could not subscribe: {self.error}")
        return self

    def stop(self, quiet_s: float = 0.3, timeout: float = 30.0,
             settle_s: float | None = None,
             progress: Callable[[BusRecorder, float], None] | None = None,
             until: int | None = None) -> RecordWriter:
        """Finish: record every message sent before this call and none sent after it, close
        the record (with this recorder's own costs in its metadata `teleo.recorder`); returns
        the writer.

        What was sent before the call is written: what waits in the subscription's queue,
        then what is still in flight, until none of it has arrived for `quiet_s` (the launch
        stops its recorder once every process has stopped, while the router may still hold
        what they published last). What is sent after the call is left out (`after_stop`),
        so a live run, whose bus never falls quiet, does not hold the stop: waiting for a
        quiet bus once made `teleo record --seconds 2` record 32 s. "Before" is by the
        sender's wall clock (env.sent_ns), which a message from another host with a clock
        behind ours, or a replayed record, can fool: `settle_s` bounds how long messages
        in flight are still taken once the queue is caught up (None: no bound). `timeout`
        bounds the whole stop, and `cut_short()` (a second Ctrl-C) ends it at once: what is
        still queued then is left out (`cut`), and the record's metadata says which cycles
        it holds. `progress(self, seconds)` is called about once a second while it drains.
        `until`: the cycles the run ran (a launch: its trace's lines); the drain does not end
        on a quiet bus before the world state of the last of them is written (a recorder
        starved of CPU reads in bursts, and a quiet spell is not the end: drill
        slow-record), unless the record cannot be written."""
        self._quiet_s, self._settle_s, self._until = quiet_s, settle_s, until
        if self._stop_ns is None:
            self._stop_ns = time.time_ns()
        self._stop.set()
        start = time.monotonic()
        while self._thread.is_alive() and not self._abandon.is_set():
            waited = time.monotonic() - start
            if waited >= timeout:
                log.warning("recorder of run %s still draining after %.0f s: the rest is not "
                            "recorded", self.run, timeout)
                self.cut_short()
                break
            self._thread.join(min(1.0, timeout - waited))
            if progress is not None and self._thread.is_alive():
                progress(self, time.monotonic() - start)
        if self._thread.is_alive():   # it ends after the message it is writing
            self._thread.join(5.0)
        self.writer.meta(RECORDER_META, {"received": str(self.received),
                                         "dropped": str(self.dropped),
                                         "after_stop": str(self.after_stop),
                                         "cut_short": str(self.cut).lower(),
                                         "drain_ms": f"{(time.monotonic() - start) * 1e3:.0f}",
                                         "cpu_ms": f"{self.cpu_s * 1e3:.1f}"})
        try:
            self.writer.close()
        except OSError as exc:  # a full disk: the file holds what was written before
            self._fail(self.last_cycle, exc)
        return self.writer

    def cut_short(self) -> None:
        """Stop draining now (safe from a signal handler: it only sets an Event)."""
        self.cut = self.cut or self._thread.is_alive()
        self._abandon.set()

    def report(self) -> dict[str, Any]:
        """What the launch's summary says of its record: the write that failed
        ({"cycle", "reason"}: nothing was written from about that cycle on), whether the stop
        left out what was still queued, the distinct cycles recorded."""
        return {"failed": dict(self.failed), "cut_short": self.cut, "cycles": self.cycles,
                "last_cycle": self.last_cycle}

    def _fail(self, cycle: int | None, exc: OSError) -> None:
        if not self.failed:
            self.failed = {"cycle": cycle, "reason": exc.strerror or str(exc)}
            log.error("record %s: cannot be written from about cycle %s on (%s); the run goes "
                      "on unrecorded", self.writer.path, cycle, exc.strerror or exc)

    def _main(self) -> None:
        try:
            with open_node(self.cfg, self.run, self.process) as node:
                inbox = node.subscribe_fifo(keys.run_all(self.run))
                if self.process == keys.RECORDER:
                    node.declare([self._own])
                    self._node = node
                if self._announce or self._node is not None:
                    node.announce()
                self._ready.set()
                self._ask_static(node)
                self._pump(inbox)
                self.cpu_s = time.thread_time()  # this thread's CPU time [s]
        except Exception as exc:  # reported by start()/the launcher, never a silent stop
            self.error = exc
            self._ready.set()
            log.error("recorder of run %s stopped: %s", self.run, exc)

    def _ask_static(self, node: Any) -> None:
        """The world's static part, asked once: a recorder that starts after the
        world published it (`teleo record` of a running launch) still holds it; a launch's
        recorder, there before the world, records what the world publishes."""
        key = keys.world_static(self.run)
        try:
            told = node.query(key, WorldStatic(node.envelope(), "driving"), STATIC_ASK_S)
        except BusError as exc:
            log.info("recorder: no answer on %s yet (%s): the world will publish it", key, exc)
            return
        if isinstance(told, WorldStatic):
            self.writer.add(key, message_record(key, told))
            self.received += 1   # an answer is a message received too

    def _pump(self, inbox: FifoInbox, most: int = 4096) -> None:
        """Take what waits every LOOK_S and write it (one wake-up for a batch, not one per
        message); once stopped, until nothing sent before the stop has arrived for
        `_quiet_s`, or `_settle_s` after the queue was first caught up (or abandoned)."""
        quiet_since = caught_up = None
        while not self._abandon.is_set():
            stopping = self._stop.is_set()  # read first: a batch that is not full then
            batch = inbox.drain(most)  # holds all that had arrived by the stop
            if self._write_all(batch):
                quiet_since = None
            elif stopping:
                quiet_since = quiet_since or time.monotonic()
            if stopping:
                now = time.monotonic()
                if caught_up is None and len(batch) < most:
                    caught_up = now  # all that had arrived by the stop is written
                if quiet_since is not None and now - quiet_since >= self._quiet_s \
                        and (self.failed or self._until is None
                             or self.writer.cycles >= self._until):
                    return
                if caught_up is not None and self._settle_s is not None \
                        and now - caught_up >= self._settle_s:
                    return
            self._tell_progress()
            if len(batch) < most:
                time.sleep(LOOK_S)

    def _tell_progress(self) -> None:
        """A launch's recorder: publish, every PROGRESS_S at most (every AGAIN_S when it has
        not moved), the last cycle it holds whole (every message of a cycle is sent before
        the next world state, so it is the one before the latest world state written; -1:
        it has the first), for the world to keep pace with."""
        whole = self.writer.cycles - 2
        now = time.monotonic()
        if whole < -1:   # nothing recorded yet: -2 is no cycle, not one to report
            return
        if self._node is None or now - self._told_at < (
                PROGRESS_S if whole > self._told else AGAIN_S):  # said again now and then:
            return                                             # a restarted world learns it
        self._told, self._told_at = whole, now
        self._node.publish(self._own, ProcessStats(self._node.envelope(whole), self.process,
                                                   0.0, 0))

    def _write_all(self, batch: list[tuple[str, bytes]]) -> int:
        """Write the messages of `batch` sent before the stop; how many were."""
        taken = 0
        for key, payload in batch:
            if self._abandon.is_set():
                break
            if key == self._own:  # its own progress: not a message of the run
                continue
            try:
                record = to_record(key, payload)
            except (CodecError, AttributeError, KeyError, TypeError, ValueError,
                    RecursionError, ArithmeticError) as exc:
                # a hostile payload never ends the recorder (the run's record with it)
                self.received += 1
                self.dropped += 1
                log.warning("not recorded: %s", exc)
                continue
            stop_ns = self._stop_ns
            if stop_ns is not None and _sent_ns(record) > stop_ns:
                self.after_stop += 1
                continue
            self.received += 1
            taken += 1
            if self.failed:  # the file cannot be written: taken off the bus all the same,
                self.dropped += 1  # so no sender waits for this subscription
                continue
            try:
                self.writer.add(key, record)
            except (CodecError, AttributeError, KeyError, TypeError, ValueError,
                    RecursionError, ArithmeticError) as exc:
                self.dropped += 1
                log.warning("not recorded: %s", exc)
                continue
            except OSError as exc:
                self.dropped += 1
                self._fail(_env(record).get("cycle"), exc)
                continue
            self._count_cycle(record)
        return taken

    def _count_cycle(self, record: dict[str, Any]) -> None:
        cycle = _env(record).get("cycle")
        if isinstance(cycle, int) and cycle >= 0:
            self._cycles.add(cycle)
            self.first_cycle = min(cycle, self.first_cycle if self.first_cycle is not None
                                   else cycle)
            self.last_cycle = max(cycle, self.last_cycle if self.last_cycle is not None else -1)


def _env(record: dict[str, Any]) -> dict[str, Any]:
    """A record's envelope, {} when a hostile payload made it something else (it crashed
    the recorder's thread, and the run's record lost the rest of the run)."""
    env = record.get("env") if isinstance(record, dict) else None
    return env if isinstance(env, dict) else {}


def _sent_ns(record: dict[str, Any]) -> int:
    """When a record's message was sent [ns] (0 when its envelope does not say: kept)."""
    sent = _env(record).get("sent_ns")
    return sent if isinstance(sent, int) else 0
