"""Pausing and stepping a lockstep run between its cycles (`teleo pause`, `teleo step-run N`,
`teleo resume`; docs/bus.md, "Pausing and stepping a launch").

The world process asks its Gate at the start of every cycle, before anything of that cycle
happens (its events, its state, the wait for the record): the gate answers the control
queries asked on teleo/<run>/world/control since the last boundary, then holds the loop for
as long as the run is paused. Nothing a cycle computes depends on how long it was held, so
the trace of a paused and stepped run is byte for byte the trace of the same run never
paused. While it is held no cycle is running: the clock's deadline, stall and restart
timeouts do not count, and every stage waits for the next state with its token up.

A request is a WorldEvent whose event is {"op": "pause"}, {"op": "resume"}, {"op": "status"}
or {"op": "step", "cycles": N}, or a change of the running launch, {"op": "load", "agent",
"name", "text"[, "at"]} (`teleo program load`) or {"op": "set", "key", "value"[, "at"]}
(`teleo set`), which the world checks (its `check`) and schedules for cycle "at" (default: the
next cycle to run), answering with that cycle; the world then hands each due change to the
cycle's state (`due`), where every stage takes it at the same cycle (docs/bus.md, "Changing a
running launch"). The answer is an EventReply whose env.cycle is the next cycle
to run and whose outcome is {"op", "paused", "cycle", "stepped"}. A pause, resume or status
is answered at the next boundary; a step when its N cycles have run and the run is held
again ("paused at cycle 123 after 3 cycles"), so the asker hears the world's verdict, not
that something was sent. A realtime run refuses to pause or step: its cycles keep wall-clock
time, and a held clock would be a different run (launch with --mode lockstep to pause it); it
takes changes as a lockstep run does.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from bus import keys
from bus.clock import CycleInterrupted
from bus.messages import EventReply, WorldEvent
from bus.pending import Pending, serve_later

OPS = ("pause", "resume", "status", "step", "load", "set")
CHANGES = ("load", "set")
MAX_STEP = 1_000_000  # [cycles] in one step-run
POLL_S = 0.02         # [s] how often a held run looks for a request or a stop
REALTIME = ("pause and step hold a lockstep run between cycles; this run is realtime (its "
            "cycles keep wall-clock time); launch it with --mode lockstep to pause it")
__all__ = ["Gate", "OPS"]


class Gate:
    """The world loop's pause point; one per world process.

    lockstep: whether the run may be held (realtime runs refuse every request); stop: the
    world's stop event (a held run raises CycleInterrupted within POLL_S of it); note: where
    each pause and resume is written (the world's health record, Recorder.event); check: the
    world's verdict on a change asked for ("" to take it, else why not)."""

    def __init__(self, node, lockstep: bool, stop: threading.Event,
                 note: Callable[..., None] | None = None,
                 check: Callable[[dict], str] | None = None) -> None:
        self.node, self.lockstep, self.stop = node, lockstep, stop
        self.note = note or (lambda kind, **fields: None)
        self.check = check or (lambda event: "this world takes no changes while it runs")
        self.changes: dict[int, list[dict]] = {}  # cycle -> the changes due at its start
        self.desk = serve_later(node, keys.world_control(node.run))
        self.paused = False
        self.left: int | None = None  # cycles of a step still to run (None: not stepping)
        self.steppers: list[tuple[Pending, int, int]] = []  # (query, asked cycles, from cycle)

    def hold(self, t: int) -> None:
        """At the start of cycle `t`: answer the requests, then wait while paused."""
        if self.left == 0:
            self.left = None
            self._settle(t)
        self._serve(t)
        held = False
        while self.paused and self.left is None:
            if not held:
                held = True
                self.note("paused", cycle=t)
            if self.stop.is_set():
                raise CycleInterrupted(t, ())
            time.sleep(POLL_S)
            self._serve(t)
        if held:
            self.note("resumed", cycle=t, stepping=self.left or 0)
        if self.left is not None:
            self.left -= 1

    def due(self, t: int) -> list[dict]:
        """The changes due at the start of cycle `t`, in the order they were asked for."""
        return self.changes.pop(t, [])

    def close(self, t: int) -> None:
        """The run has ended at cycle `t`: every request still open gets that reason."""
        for pending, _, _ in self.steppers:
            pending.fail(f"the run ended at cycle {t} before the step was done")
        self.steppers = []
        self.desk.close(f"the run ended at cycle {t}")

    def _serve(self, t: int) -> None:
        for pending in self.desk.take():
            event = pending.request.event if isinstance(pending.request, WorldEvent) else None
            op = event.get("op") if isinstance(event, dict) else None
            if op not in OPS:
                pending.fail(f"control: expected {{\"op\": one of {list(OPS)}}}, got {event!r}")
            elif op in CHANGES:
                self._change(pending, event, t)
            elif not self.lockstep:
                pending.fail(REALTIME)
            elif op == "step":
                self._step(pending, event.get("cycles", 1), t)
            else:
                if op == "pause" or op == "resume":
                    was = self.paused
                    self.paused = op == "pause"
                    if self.left is not None:  # a pause or resume ends a step in progress
                        self.left = None
                        self._settle(t)
                    reason = "" if was != self.paused else f"already {op}d"
                    self._answer(pending, t, op, reason)
                else:
                    self._answer(pending, t, op, "")

    def _step(self, pending: Pending, cycles: Any, t: int) -> None:
        if not isinstance(cycles, int) or isinstance(cycles, bool) or not 1 <= cycles <= MAX_STEP:
            pending.fail(f"control: step: cycles: expected a whole number in [1, {MAX_STEP}], "
                         f"got {cycles!r}")
        elif self.left is not None:
            pending.fail(f"control: a step is in progress ({self.left} cycles to go); "
                         "wait for it, or pause or resume first")
        else:
            self.paused, self.left = True, cycles
            self.steppers.append((pending, cycles, t))

    def _change(self, pending: Pending, event: dict, t: int) -> None:
        event = dict(event)   # the world's check adds what it made of it
        at = event.get("at", t)
        if not isinstance(at, int) or isinstance(at, bool) or at < t:
            pending.fail(f"control: {event['op']}: at: expected a cycle >= {t} (the next to "
                         f"run), got {at!r}")
            return
        why = self.check(event)
        if why:
            pending.fail(f"control: {event['op']}: {why}")
            return
        self.changes.setdefault(at, []).append(event)
        said = {k: event[k] for k in ("agent", "name", "key", "value") if k in event}
        self._answer(pending, at, str(event["op"]), "", said=said)

    def _settle(self, t: int) -> None:
        """Answer the step in progress: it ended at cycle `t` (done, or a pause or resume)."""
        for pending, _, start in self.steppers:
            self._answer(pending, t, "step", "", stepped=t - start)
        self.steppers = []

    def _answer(self, pending: Pending, t: int, op: str, reason: str, stepped: int = 0,
                said: dict | None = None) -> None:
        outcome = {"op": op, "paused": self.paused, "cycle": t, "stepped": stepped,
                   **(said or {})}
        pending.answer(EventReply(self.node.envelope(t), True, reason, outcome))
