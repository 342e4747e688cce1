"""The agent-side loop of one stage (perception, inference or executive).

    stage = Stage(node, "ME.inference", [keys.percepts(run, "ME")], step,
                  outputs=[keys.beliefs(run, "ME")])
    stage.run(stop)          # stop: threading.Event set from SIGINT/SIGTERM handlers

`step(cycle, {input_key: msg}) -> [(key, msg), ...]` is called once per cycle with the
inputs of exactly that cycle. The stage publishes what `step` returned, its stats carried in
the first output whose kind has a ``stats`` field (with the stats its inputs carried: an
agent's Actions hold its whole pipeline's; bus/stats.py), or in a ProcessStats of their own
when no output can carry them. A stage idle for `quiet_s` after a cycle also sends that
cycle's ProcessStats alone: a stalled or late cycle is then attributed by the clock to the
first stage that has not said it is done (docs/bus.md, "Stage stats"), while a fast lockstep
cycle sends no stats message at all.
A cycle seen again (the clock re-sent state t for a restarted stage) re-emits the cached
outputs without calling `step` again; cycles older than the last handled one are dropped;
when it has fallen behind it skips to the newest complete cycle and counts the skipped
ones in ProcessStats.late. A step that raises bus.errors.Refused (its inputs are malformed)
publishes nothing and leaves the cycle undone: the next copy of it is handled as new.
"""

from __future__ import annotations

import logging
import signal
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import replace

from bus import keys
from bus.collector import Collector
from bus.cycle import Joined, Joiner, pick
from bus.errors import Refused
from bus.lifeline import hold_on_to_parent
from bus.messages import Message, ProcessStats
from bus.node import Inbox, Node
from bus.stats import STATS_FIELD, stats_of

log = logging.getLogger(__name__)


def stop_on_signals(child: bool = False) -> threading.Event:
    """An Event set by SIGINT or SIGTERM (installs the handlers; call from the main thread).

    SIGINT is installed explicitly, so it works even where the process was started with it
    ignored (a background job of a non-interactive shell). `child=True` (processes of a
    launch) also ties the process to its launcher: it stops when the launcher dies
    (bus/lifeline.py)."""
    stop = threading.Event()

    def handler(signum: int, frame: object) -> None:
        if not stop.is_set():
            log.info("signal %s: stopping", signal.Signals(signum).name)
        stop.set()

    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, handler)
    if child:
        hold_on_to_parent()
    return stop


QUIET_S = 0.02
"""Stage.quiet_s's default [s]: above a lockstep cycle of the demo, far below
the clock's deadline (2 s), stall threshold (1 s) and a realtime period (50 ms and up)."""

StepFn = Callable[[int, dict[str, Message]], list[tuple[str, Message]]]


class Stage:
    """Joins `inputs` (exact keys) by cycle, calls `step_fn`, publishes outputs and stats.

    outputs: keys that must have a subscriber before the stage announces itself (the
    start-up barrier); other keys returned by `step_fn` are declared on first use.
    stages: the stage processes this Stage runs the steps of, when it runs several (a shared
    process: agents/processes/shared.py); they are announced with the node, and `step_fn`
    returns their stats carried in its outputs, each stage's in the output it sent (the
    ``stats`` field, as a stage of its own carries them; bus/stats.py), which the Stage
    sends alone, one ProcessStats per stage, once idle after a cycle.
    early: called with an input message of a cycle still incomplete when the stage would
    otherwise wait for the rest of it (a shared process starts its agents' perception and
    inference on the world state while their goal lists are on the way); what it computes
    is for `step_fn` to use.
    quiet_s: after a cycle, idle this long [s] (no input came), the stage sends that cycle's
    ProcessStats alone: well below the clock's deadline, stall threshold and realtime period,
    well above a fast lockstep cycle (docs/bus.md, "Stage stats").
    """

    def __init__(self, node: Node, process: str, inputs: Sequence[str], step_fn: StepFn,
                 outputs: Sequence[str] = (), ready_timeout: float = 10.0,
                 stages: Sequence[str] = (),
                 early: Callable[[str, Message], None] | None = None,
                 quiet_s: float = QUIET_S) -> None:
        self.node = node
        self.early = early
        self.process = keys.check_chunk(process, "process")
        self.step_fn = step_fn
        self.outputs = tuple(outputs)
        self.ready_timeout = ready_timeout
        self.joiner = Joiner(inputs)
        self.late = 0
        self.cycles_done = 0
        self.refused = 0  # cycles whose inputs the step refused (bus.errors.Refused)
        self._stats_key = keys.stats(node.run, self.process)
        self._cache: list[tuple[str, Message]] = []
        self._inbox: Inbox | None = None
        self.stages = tuple(stages)
        self.quiet_s = quiet_s
        # the last cycle's stats, not yet sent alone: its ProcessStats, or (stages) the
        # outputs that carry each stage's
        self._quiet: list[tuple[str, Message]] | None = None

    @property
    def inbox(self) -> Inbox:
        if self._inbox is None:
            raise RuntimeError(f"stage {self.process}: start() not called")
        return self._inbox

    def start(self) -> None:
        """Subscribe, declare publishers, wait (bounded) for `outputs` to match, announce."""
        inbox = Inbox()
        for key in self.joiner.inputs:
            self.node.subscribe(key, inbox=inbox)
        self.node.declare([*self.outputs, self._stats_key])
        unmatched = self.node.wait_matching(self.outputs, self.ready_timeout)
        if unmatched:
            log.warning("%s: no subscriber yet on %s after %.1f s; announcing anyway",
                        self.process, sorted(unmatched), self.ready_timeout)
        self._inbox = inbox
        self.node.announce(self.stages)

    def run(self, stop: threading.Event, poll_s: float = 0.1) -> None:
        """Handle cycles until `stop` is set (checked every `poll_s` [s] when idle)."""
        if self._inbox is None:
            self.start()
        collector = Collector()
        try:
            while not stop.is_set():
                if self.step_once(poll_s) is not None:
                    collector.after_cycle()
        finally:
            collector.close()

    def step_once(self, timeout: float) -> int | None:
        """Wait up to `timeout` [s] for input, handle the newest complete cycle in the
        inbox; return its number, or None if no cycle completed."""
        quiet = self._quiet is not None and timeout > self.quiet_s
        first = self.inbox.receive(self.quiet_s if quiet else timeout)
        if first is None:
            if self._quiet is not None and (quiet or timeout >= self.quiet_s):
                self.node.publish_many(self._alone(self._quiet))  # idle: say it is done
                self._quiet = None
            return None
        batch = [self.joiner.add(first.key, first.msg)]
        newest = {first.key: first.msg}
        while (more := self.inbox.receive(0)) is not None:
            batch.append(self.joiner.add(more.key, more.msg))
            newest[more.key] = more.msg
        joined, skipped = pick(batch)
        if joined is None:
            self._early(newest)
            return None
        self.late += skipped
        self._handle(joined)
        return joined.cycle

    def _early(self, newest: dict[str, Message]) -> None:
        """Hand `early` the newest message of each key just drained whose cycle is still to
        be handled: only while the stage would otherwise wait for the rest of a cycle, and
        never ahead of an older cycle that may still complete (the steps see their cycles in
        order: a stage that has fallen behind, in a realtime run, waits as before)."""
        if self.early is None:
            return
        done = self.joiner.last_done
        for key, msg in newest.items():
            cycle = msg.env.cycle
            if key in self.joiner.inputs and (done is None or cycle > done) \
                    and not self.joiner.pending_before(cycle):
                self.early(key, msg)

    def _handle(self, joined: Joined) -> None:
        if joined.repeat:
            log.info("%s: cycle %d seen again; re-emitting cached outputs", self.process,
                     joined.cycle)
            outs, compute_ms = self._cache, 0.0
        else:
            t0 = time.perf_counter()
            try:
                outs = list(self.step_fn(joined.cycle, joined.inputs))
            except Refused as exc:
                self.refused += 1
                log.warning("%s: cycle %d refused: %s", self.process, joined.cycle, exc)
                return
            compute_ms = (time.perf_counter() - t0) * 1e3
            self._cache = outs
            self.cycles_done += 1
        self.joiner.done(joined.cycle)
        if self.stages:
            self._quiet = outs
            self.node.publish_many(outs)
            return
        stats = ProcessStats(self.node.envelope(joined.cycle), self.process, compute_ms,
                             self.late)
        if joined.repeat:  # the cached outputs carry that cycle's stats already, if any
            carried = outs if any(getattr(m, STATS_FIELD, None) for _, m in outs) else None
        else:
            carried = self._carry(outs, joined.inputs, stats)
        if carried is None:  # no output can carry them: on their own, before the outputs
            self.node.publish_many([(self._stats_key, stats), *outs])
            return
        self._cache, self._quiet = carried, [(self._stats_key, stats)]
        self.node.publish_many(carried)

    def _alone(self, quiet: list[tuple[str, Message]]) -> list[tuple[str, Message]]:
        """The ProcessStats that say the last cycle is done (see `_quiet`)."""
        if not self.stages:
            return quiet
        return [(keys.stats(self.node.run, s.process), s) for _, m in quiet
                for s in stats_of(m, own=True)]

    def _carry(self, outs: list[tuple[str, Message]], inputs: dict[str, Message],
               stats: ProcessStats) -> list[tuple[str, Message]] | None:
        """`outs` with `stats` (and those the inputs carried) in the first output that has a
        stats field; None when none has."""
        for i, (key, msg) in enumerate(outs):
            if STATS_FIELD in msg.__dataclass_fields__:   # a kind with a stats field
                merged: dict[str, list] = {}
                for m in inputs.values():
                    merged.update(getattr(m, STATS_FIELD, None) or {})
                merged[self.process] = [stats.compute_ms, stats.late]
                return [*outs[:i], (key, replace(msg, stats=merged)), *outs[i + 1:]]
        return None

