"""The world side of the cognitive cycle: the world is the clock (docs/bus.md,
"The cycle").

    clock = Clock(node, {"ME": ["ME.perception", "ME.inference", "ME.executive"]})
    clock.wait_ready({"ME.perception", "ME.inference", "ME.executive"}, timeout=30)
    for t in itertools.count():
        report = clock.run_cycle(t, WorldState(node.envelope(t), snapshot, outcomes, []))
        apply(report.actions)          # agent -> tuple of action lists; () is the no-op

Lockstep: state t is published, then the clock waits for the Actions of t from every agent
whose stages are all alive. A stage that misses the per-cycle deadline while its token is
still there (hung, SIGSTOPped) is reported in `late` and its agent gets the no-op. A stage
whose token disappears (crash) is waited for up to `restart_timeout_s`; when it (or any
stage) comes back, state t is re-sent so it rejoins at the current cycle; a cycle still
waiting re-sends it every `resend_s` anyway (a sample lost in a reconnect). If it is not
back in time: policy CONTINUE counts it in `dead`, gives its agent the no-op and stops
waiting for it until it returns; policy STOP raises ClockStopped.
Realtime: a fixed period; whatever has not arrived by the end of the period is the no-op
(`late`); a vanished stage is reported in `dead` at once, and the policy applies once it
has been gone longer than the restart timeout.

Every wait is interruptible: with a `stop` event, `wait_ready` and `run_cycle` raise
CycleInterrupted within one poll (POLL_S) of it being set (Ctrl-C during a stall). A lockstep
cycle that waits longer than `stall_s` names the stages it was waiting for in
`CycleReport.stalled`, so a run's summary shows stalls that recovered.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Mapping, Sequence

from bus import keys
from bus.cycle import CycleMode, CycleReport, DeadPolicy
from bus.cycle_wait import POLL_S, CycleInterrupted, CycleRun
from bus.errors import ClockStopped, NotReady, PaceLost
from bus.load import scaled
from bus.messages import ProcessStats, WorldState
from bus.node import Node

log = logging.getLogger(__name__)


class Clock:
    """Publishes world states and collects actions; one per run, in the world process.

    pipelines: agent -> its stage process names in pipeline order (used to name the late
    stage); period_s: realtime period [s]; deadline_s: lockstep per-cycle deadline [s];
    restart_timeout_s: how long lockstep waits for a vanished stage to come back [s];
    stall_s: a lockstep cycle waiting longer than this is reported as stalled [s];
    resend_s: a lockstep cycle still waiting re-publishes its state this often [s];
    stop: an event that interrupts any wait (CycleInterrupted).
    """

    def __init__(self, node: Node, pipelines: Mapping[str, Sequence[str]], *,
                 mode: CycleMode = CycleMode.LOCKSTEP, period_s: float = 0.1,
                 deadline_s: float = 2.0, restart_timeout_s: float = 5.0,
                 policy: DeadPolicy = DeadPolicy.CONTINUE, stall_s: float = 1.0,
                 resend_s: float = 1.0, stop: threading.Event | None = None) -> None:
        self.node = node
        self.stall_s, self.resend_s = stall_s, resend_s
        self.stop = stop if stop is not None else threading.Event()
        self.pipelines = {a: tuple(p) for a, p in pipelines.items()}
        self.mode = CycleMode(mode)
        self.period_s, self.deadline_s = period_s, deadline_s
        self.restart_timeout_s, self.policy = restart_timeout_s, DeadPolicy(policy)
        self.last_seen: dict[str, int] = {}
        self.dead: set[str] = set()  # stages given up on (policy CONTINUE) until they return
        self.gone_since: dict[str, float] = {}  # stage -> when its token was first missed [s]
        self._state_key = keys.world_state(node.run)
        self.inbox = node.subscribe(keys.all_actions(node.run))
        # stats are read only when needed (deadline, report): a ring buffer, so the three
        # stats per agent and cycle do not wake this process (a wake-up per message costs the
        # world's cycle more than reading them all at once)
        self.stats = node.subscribe_ring(keys.all_stats(node.run))
        node.declare([self._state_key])
        self._incarnations = dict(node.presence.incarnations())
        self._next_start: float | None = None
        self._stuck: dict[str, int] = {}  # keep_pace: process -> the cycle it was given up at
        self._first = True  # run_cycle: the first cycle is a handshake (see there)

    def wait_ready(self, expected: set[str], timeout: float) -> None:
        """Start-up barrier: wait until every process in `expected` holds its token and
        the world state has a subscriber; raise NotReady (naming the missing) on timeout."""
        deadline = time.monotonic() + timeout
        while not self.node.presence.wait_for(lambda alive: expected <= alive, POLL_S * 5):
            if self.stop.is_set():
                raise CycleInterrupted(-1, set(expected) - self.node.alive())
            if time.monotonic() >= deadline:
                raise NotReady(set(expected) - self.node.alive(), timeout)
        if self.pipelines and self.node.wait_matching([self._state_key],
                                                      max(0.0, deadline - time.monotonic())):
            raise NotReady(set(), timeout, f"no subscriber on {self._state_key}")
        self._incarnations = dict(self.node.presence.incarnations())
        self._first = True   # the next cycle is the first since every stage announced itself

    def run_cycle(self, cycle: int, state_msg: WorldState,
                  meanwhile: Callable[[], object] | None = None) -> CycleReport:
        """Publish state `cycle` and collect the agents' actions of `cycle` (see module doc).
        `meanwhile` runs right after the state is out, while the agents work on it: the
        world's bookkeeping of that state, off the cycle's critical path."""
        if self.mode is CycleMode.REALTIME:
            self._pace()
        for p in self._rejoined() & self.node.presence.snapshot():  # came back in between
            self.dead.discard(p)
            self.gone_since.pop(p, None)
        start = time.monotonic()
        self.node.publish(self._state_key, state_msg)
        if meanwhile is not None:
            meanwhile()
        # the first cycle after start-up waits for every stage as lockstep does, sending its
        # state again until each answers: a token is up before its subscriptions reach every
        # publisher, and a realtime run would lose cycle 0 to that race
        run = CycleRun(self, cycle, state_msg, start, handshake=self._first)
        self._first = False
        run.wait()
        report = run.report(time.monotonic())
        if report.late or report.dead:
            log.warning("cycle %d: late %s, dead %s, no-op for %s", cycle, list(report.late),
                        list(report.dead), list(report.noop))
        if run.stopped:
            raise ClockStopped(cycle, report.dead, report)
        return report

    def keep_pace(self, process: str, cycle: int, stuck_s: float = 10.0,
                  resend: WorldState | None = None, required_s: float | None = None
                  ) -> float:
        """Wait until `process` (not a stage: the launch's recorder) has reported, in its
        ProcessStats, cycle `cycle` or a later one (-1: it has begun); returns the seconds
        waited [s]. A stop interrupts it (CycleInterrupted).

        Not `required_s` (None): no wait while its token is absent (no recorder, or it
        died), nor once it has made no progress for `stuck_s` [s] (until it moves again).
        `required_s` [s]: the run must not outrun it (a launch that records: a world
        that ran on would lose cycles from its record): it is
        waited for as a stage is, while it is absent or not moving, and when it has been
        absent or still for `required_s` (stretched by the machine's load, bus/load.py)
        PaceLost is raised: the run stops rather than run cycles it would not record.

        `resend`: the state to publish again every `resend_s` while it waits (a state it
        may have missed: the stages answer it from their caches). Lockstep only: what a run
        sends while a subscriber lags waits in the senders' queues, and a process that stops
        drops what its queue still holds (tests/e2e/test_record_drain.py)."""
        self._note_stats()
        seen = self.last_seen.get(process, -2)
        present = process in self.node.presence.snapshot()
        if seen >= cycle or required_s is None and (self._stuck.get(process) == seen
                                                    or not present):
            return 0.0  # there, stuck at the cycle it was given up at (until it moves), gone
        start = moved = sent = time.monotonic()
        gone_since = None if present else start
        while self.last_seen.get(process, -2) < cycle:
            if self.stop.is_set():
                raise CycleInterrupted(cycle, {process})
            now = time.monotonic()
            if process not in self.node.presence.snapshot():
                if required_s is None:
                    break
                if gone_since is None:
                    log.warning("%s left the bus at cycle %d: the world waits for it", process,
                                cycle)
                    gone_since = now
                if now - gone_since > scaled(required_s):
                    raise PaceLost(f"{process} left the bus at cycle {cycle} and was not back "
                                   f"within {now - gone_since:.0f} s: no cycle runs that it "
                                   f"would not record")
            elif gone_since is not None:
                gone_since, moved = None, now   # back: its time to move starts again
            if required_s is not None and gone_since is None \
                    and now - moved > scaled(required_s):
                raise PaceLost(f"{process} has not moved from cycle {seen} for "
                               f"{now - moved:.0f} s: no cycle runs that it would not record")
            if required_s is None and now - moved > stuck_s:
                log.warning("%s has not moved from cycle %d for %.0f s: not waited for",
                            process, seen, stuck_s)
                self._stuck[process] = seen
                break
            if resend is not None and now - sent >= self.resend_s:
                self.node.publish(self._state_key, resend)
                sent = now
            time.sleep(POLL_S)
            self._note_stats()
            if self.last_seen.get(process, -2) > seen:
                seen, moved = self.last_seen[process], time.monotonic()
        return time.monotonic() - start

    def _note_stats(self) -> None:
        """Take the stats waiting in the ring into `last_seen` (the stages' figures of the
        cycle in progress are taken again from the same ring by its CycleRun, bus/cycle_wait.py)."""
        for item in self.stats.drain():
            if isinstance(item.msg, ProcessStats):
                prev = self.last_seen.get(item.msg.process, -1)
                self.last_seen[item.msg.process] = max(prev, item.msg.env.cycle)

    def _pace(self) -> None:
        now = time.monotonic()
        if self._next_start is None or now - self._next_start > self.period_s:
            self._next_start = now  # first cycle, or overran a whole period: no catch-up burst
        elif self._next_start > now:
            time.sleep(self._next_start - now)  # fixed-rate pacing, not synchronisation
        self._next_start += self.period_s

    def _rejoined(self) -> set[str]:
        """Stages that (re)appeared since last checked (a new incarnation of the token)."""
        now = self.node.presence.incarnations()
        new = {p for p, n in now.items() if n != self._incarnations.get(p)}
        self._incarnations = dict(now)
        return new


__all__ = ["Clock", "CycleInterrupted"]
