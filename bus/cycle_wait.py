"""One lockstep or realtime cycle's wait, for the Clock (bus/clock.py): collect every agent's
actions of the cycle, re-send the state to a stage that came back or may have lost it, give
the no-op to an agent whose stages are late or gone, and name the stages a stall waits for."""

from __future__ import annotations

import logging
import time
from collections.abc import Sequence
from typing import Any

from bus.cycle import CycleBook, CycleMode, CycleReport, DeadPolicy, culprit
from bus.errors import BusError
from bus.messages import WorldState

log = logging.getLogger("bus.clock")
POLL_S = 0.02
"""How often liveliness and deadlines are looked at while waiting for actions [s]."""


class CycleInterrupted(BusError):
    """The clock's stop event was set while it waited (a signal asked the world to stop)."""

    def __init__(self, cycle: int, waiting: Sequence[str], stalled: Sequence[str] = (),
                 waited_s: float = 0.0) -> None:
        what = f"waiting for {', '.join(sorted(waiting))}" if waiting else "waiting"
        super().__init__(f"cycle {cycle}: interrupted while {what}")
        self.cycle = cycle
        self.stalled = tuple(stalled)  # a stall in progress at the stop: the stages it waited
        self.waited_s = waited_s       # on, and how long [s] (listed at the stop)


class CycleRun:
    """The waiting loop of one cycle of a Clock (bus/clock.py): what has come, who is late,
    gone or stalled, and the cycle's report."""

    def __init__(self, clock: Any, cycle: int, state: WorldState, start: float,
                 handshake: bool = False) -> None:
        self.c, self.cycle, self.state = clock, cycle, state
        self.book = CycleBook(cycle, frozenset(clock.pipelines))
        self.waiting = set(clock.pipelines)
        self.since = {a: start for a in clock.pipelines}  # per-agent deadline origin
        self.late: list[str] = []
        self.dead: list[str] = []
        self.noop: list[str] = []
        self.republished = 0
        self.stalled: list[str] = []
        self.stopped = False
        self.start = start
        self.sent = start  # when state t was last (re)published
        self.checked = float("-inf")  # when `_check` last ran (monotonic [s])
        self.end = start + clock.period_s \
            if clock.mode is CycleMode.REALTIME and not handshake else None

    def wait(self) -> None:
        while self.waiting:
            if self.c.stop.is_set():
                waited = time.monotonic() - self.start
                if not self.stalled and self.end is None and waited > self.c.stall_s:
                    self._note_stall(self.c.node.presence.snapshot())
                raise CycleInterrupted(self.cycle, self.waiting, self.stalled, waited)
            now = time.monotonic()
            # liveliness, deadlines and re-sends are looked at every poll, not again at each
            # message that woke the loop (several agents' actions come in several wake-ups)
            if now - self.checked >= POLL_S or self.end is not None and now >= self.end:
                self.checked = now
                self._check(now)
            if self.stopped or not self.waiting:
                return
            timeout = POLL_S
            if self.end is not None:
                timeout = max(0.0, min(POLL_S, self.end - time.monotonic()))
            item = self.c.inbox.receive(timeout)
            while item is not None:
                self.book.record(item.msg, self.c.last_seen)
                item = self.c.inbox.receive(0)
            self.waiting = {a for a in self.waiting if not self.book.has(a)}

    def _check(self, now: float) -> None:
        alive = self.c.node.presence.snapshot()
        rejoined = self.c._rejoined() & alive
        if rejoined:
            self.c.dead -= rejoined
            for p in rejoined:
                self.c.gone_since.pop(p, None)
            agents = {a for a, pipe in self.c.pipelines.items() if rejoined & set(pipe)}
            if agents & self.waiting:
                log.info("cycle %d: %s back; re-publishing state", self.cycle, sorted(rejoined))
                self._resend(now)
                for a in agents:
                    self.since[a] = now
        if self.end is None and self.waiting and now - self.sent >= self.c.resend_s:
            # a sample lost while a stage was cut off (a reconnect re-declares its token and
            # its subscriptions in no set order) would hold the cycle until the deadline:
            # every stage answers a repeated state with its cached outputs, so send it again
            self._resend(now)
        for agent in sorted(self.waiting):
            self._check_agent(agent, alive, now)
        if not self.stalled and self.end is None and now - self.start > self.c.stall_s:
            self._note_stall(alive)

    def _resend(self, now: float) -> None:
        self.c.node.publish(self.c._state_key, self.state)
        self.republished += 1
        self.sent = now

    def _note_stall(self, alive: frozenset[str]) -> None:
        """Name what this cycle waits for: a gone stage, else the first one behind."""
        self._read_stats()
        for agent in sorted(self.waiting):
            pipe = self.c.pipelines[agent]
            gone = [p for p in pipe if p not in alive]
            self.stalled += gone or [culprit(pipe, self.c.last_seen, self.cycle)]
        log.warning("cycle %d: stalled, waiting for %s", self.cycle, sorted(set(self.stalled)))

    def _check_agent(self, agent: str, alive: frozenset[str], now: float) -> None:
        pipe = self.c.pipelines[agent]
        missing = [p for p in pipe if p not in alive]
        if missing:
            for p in missing:
                self.c.gone_since.setdefault(p, now)
            overdue = now - min(self.c.gone_since[p] for p in missing) > self.c.restart_timeout_s
            if overdue or all(p in self.c.dead for p in missing):
                self._give_up(agent, dead=missing, final=True)
            elif self.end is not None:  # realtime does not wait for a restart
                self._give_up(agent, dead=missing, final=False)
            return
        due = self.end if self.end is not None else self.since[agent] + self.c.deadline_s
        if now >= due:
            self._read_stats()
            self._give_up(agent, late=culprit(pipe, self.c.last_seen, self.cycle))

    def _read_stats(self) -> None:
        for item in self.c.stats.drain():
            self.book.record(item.msg, self.c.last_seen)

    def _give_up(self, agent: str, dead: Sequence[str] = (), late: str | None = None,
                 final: bool = False) -> None:
        """No-op for `agent` this cycle; `final`: its dead stages are past the restart
        timeout (policy STOP stops; CONTINUE stops waiting for them in later cycles)."""
        self.waiting.discard(agent)
        self.noop.append(agent)
        if late is not None:
            self.late.append(late)
        self.dead.extend(dead)
        if dead and final:
            if self.c.policy is DeadPolicy.STOP:
                self.stopped = True
            self.c.dead.update(dead)

    def report(self, now: float) -> CycleReport:
        self._read_stats()
        actions = {a: self.book.actions.get(a, ()) for a in self.c.pipelines}
        for a in self.noop:
            actions[a] = ()
        return CycleReport(
            cycle=self.cycle, actions=actions, late=_unique(self.late), dead=_unique(self.dead),
            noop=tuple(self.noop), republished=self.republished,
            elapsed_ms=(now - self.start) * 1e3, stage_ms=dict(self.book.stage_ms),
            stalled=_unique(self.stalled),
            memory={a: m for a, m in self.book.memory.items() if a not in self.noop})


def _unique(names: Sequence[str]) -> tuple[str, ...]:
    """In first-seen order without repeats (a stage shared by several agents, e.g. "goals")."""
    return tuple(dict.fromkeys(names))
