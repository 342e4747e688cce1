"""Where the web view's records come from: the bus (one subscriber for the whole page, and
the run's liveliness tokens for the process list), or a run record file read at once."""

from __future__ import annotations

import logging
import os
import threading
import time
from pathlib import Path

from bus import keys
from bus.errors import BusError, CodecError
from bus.messages import GoalRequest, WorldStatic
from bus.node import open_node
from bus.presence import Presence
from bus.record import message_record, to_record
from tools.records.run_record import RUN_META, RunRecord
from tools.runs import runfile
from tools.runs.target import Target
from tools.view.model import MALFORMED, ViewModel

log = logging.getLogger(__name__)
LEARN_RUN_S = 30.0  # [s] a view of a named router waits this long for a first message
ASK_TIMEOUT_S, ASK_EVERY_S, ASK_TRIES = 2.0, 5.0, 3  # the goal store's list, asked at start


def load_file(model: ViewModel, path: Path) -> None:
    """Feed every record of a run record file (the page can then step through all of it)."""
    rec = RunRecord(path)
    model.source, model.recorded = f"record {path}", True
    model.programs.from_scenario(rec.meta.get(RUN_META, {}).get("scenario", ""))
    for key, record in rec.records():
        model.add(key, record)


def scenario_of(run: str | None) -> tuple[str, str]:
    """The scenario file of the running launch of `run` and the folder the launch ran in,
    from the run registry (both "" when no launch of it is registered: a replay, or a
    router named with --connect)."""
    try:
        info = runfile.find(run) if run else None
    except runfile.NoRunningLaunch:
        info = None
    return (info.scenario, info.cwd) if info else ("", "")


class BusFeed:
    """Subscribes to the followed run (or, when none is named, to teleo/** until the first
    message names one) and feeds the model on a thread of its own."""

    def __init__(self, model: ViewModel, target: Target) -> None:
        self.model, self.target = model, target
        self.error: str | None = None
        self.stop = threading.Event()
        self.ready = threading.Event()
        self._thread = threading.Thread(target=self._main, name="teleo-view-feed", daemon=True)
        self._asked: set[str] = set()   # agents whose goal-store list was read
        self._tries, self._next_ask = 0, 0.0

    def start(self, timeout: float = 30.0) -> BusFeed:
        self.model.source = f"live: {self.target.who}"
        self._thread.start()
        self.ready.wait(timeout)
        if self.error:
            raise BusError(self.error)
        return self

    def close(self) -> None:
        self.stop.set()
        self._thread.join(5.0)

    def _main(self) -> None:
        run = self.model.run or self.target.run
        try:
            with open_node(self.target.cfg, run or "view", f"view-{os.getpid()}") as node:
                inbox = node.subscribe(keys.run_all(run) if run else f"{keys.ROOT}/**", raw=True)
                self.ready.set()
                presence = Presence(node.session, run) if run else None
                while not self.stop.is_set():
                    self._pump(inbox, 0.2)
                    self._static(node)
                    self._past_goals(node)
                    if presence is None and self.model.run:
                        presence = Presence(node.session, self.model.run)
                    if presence is not None and presence.incarnations():  # a replay has none
                        self.model.set_presence(presence.snapshot(), presence.incarnations())
        except BusError as exc:
            self.error = str(exc)
            self.ready.set()
            log.error("view feed stopped: %s", exc)

    def _static(self, node) -> None:
        """Ask the world for its static part when a world state came without it (the view
        opened after the world published it); a replay answers as the world."""
        run = self.model.run
        if run is None or not self.model.wants_static:
            return
        try:
            told = node.query(keys.world_static(run), WorldStatic(node.envelope(), "driving"),
                              ASK_TIMEOUT_S)
        except BusError as exc:
            log.info("view: the world did not give its static part: %s", exc)
            return
        if isinstance(told, WorldStatic):
            self.model.add(keys.world_static(run), message_record(keys.world_static(run), told))

    def _past_goals(self, node) -> None:
        """Ask the goal-entry process once for each agent's goals (retried a few times: a
        replay has none): those that failed or were cancelled before the view opened are
        in no message it will see."""
        run, now = self.model.run, time.monotonic()
        if run is None or now < self._next_ask or self._tries >= ASK_TRIES:
            return
        for agent in sorted(self.model.agents - self._asked):
            try:
                reply = node.query(keys.goals(run, agent), GoalRequest(
                    node.envelope(), "list", agent), ASK_TIMEOUT_S)
            except BusError as exc:
                self._tries, self._next_ask = self._tries + 1, now + ASK_EVERY_S
                log.info("view: the goal-entry process did not list the goals: %s", exc)
                return
            if getattr(reply, "ok", False):
                self.model.past_goals(agent, reply.goals)
                self._asked.add(agent)

    def _pump(self, inbox, seconds: float) -> None:
        end = time.monotonic() + seconds
        while (left := end - time.monotonic()) > 0:
            item = inbox.receive(min(left, 0.05))
            if item is None:
                continue
            try:
                self.model.add(item.key, to_record(item.key, item.payload), len(item.payload),
                               item.t_ns)
            except (CodecError, *MALFORMED) as exc:  # a record is only shape-checked
                log.warning("view: dropped %s: %r", item.key, exc)
