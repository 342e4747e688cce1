"""The goal histories of a launch that keeps no record (`teleo launch --no-record`, whose
summary shows each goal's history as simulate's and a recorded launch's do): the launcher takes
the agents' intentions and goal lists off the bus into a GoalHistory, as the recorder would,
and writes the histories to the run folder (`GOAL_HISTORY`) at the stop, where the summary
finds them (tools/records/goal_reports.py with_history)."""

from __future__ import annotations

import json
import logging
import threading
import time
from pathlib import Path
from typing import Any

from bus import keys
from bus.config import BusConfig
from bus.errors import BusError, CodecError
from bus.node import open_node
from bus.record import to_record
from tools.records.run_record import GOAL_HISTORY, GoalHistory

log = logging.getLogger(__name__)
LOOK_S = 0.05  # [s] how often what arrived is taken


class GoalWatch:
    """Subscribes to every agent's intention and goal list of `run` on a thread of its own;
    `stop()` takes what is still arriving (until `quiet_s` without any) and writes the
    histories to `run_dir`/GOAL_HISTORY."""

    def __init__(self, cfg: BusConfig, run: str, run_dir: Path) -> None:
        self.cfg, self.run, self.path = cfg, run, Path(run_dir) / GOAL_HISTORY
        self.history = GoalHistory()
        self._ready, self._stop = threading.Event(), threading.Event()
        self._quiet_s, self._until = 0.3, 0.0
        self.error: BaseException | None = None
        self._thread = threading.Thread(target=self._main, name="teleo-goal-watch",
                                        daemon=True)

    def start(self, timeout: float = 30.0) -> GoalWatch:
        self._thread.start()
        if not self._ready.wait(timeout) or self.error is not None:
            raise BusError(f"goal histories of run {self.run}: could not subscribe: "
                           f"{self.error}")
        return self

    def stop(self, quiet_s: float = 0.3, timeout: float = 10.0) -> None:
        """Take what still arrives, then write the histories (a failed write is logged)."""
        self._quiet_s, self._until = quiet_s, time.monotonic() + timeout
        self._stop.set()
        self._thread.join(timeout + 1.0)
        try:
            self.path.write_text(json.dumps(dict(self.history.changes)))
        except OSError as exc:
            log.error("goal histories %s: not written (%s)", self.path, exc.strerror or exc)

    def _main(self) -> None:
        try:
            with open_node(self.cfg, self.run, f"goal-watch-{id(self):x}") as node:
                every = keys.intention(self.run, "A").rsplit("/", 2)[0] + "/*/"  # any agent
                inboxes = [node.subscribe_fifo(every + keys.intention(self.run, "A")
                                               .rsplit("/", 1)[1]),
                           node.subscribe_fifo(every + keys.goal_list(self.run, "A")
                                               .rsplit("/", 1)[1])]
                self._ready.set()
                quiet_since: float | None = None
                while True:
                    taken = sum(self._take(inbox.drain()) for inbox in inboxes)
                    now = time.monotonic()
                    if self._stop.is_set():
                        quiet_since = None if taken else (quiet_since or now)
                        if now >= self._until or quiet_since is not None \
                                and now - quiet_since >= self._quiet_s:
                            return
                    if not taken:
                        time.sleep(LOOK_S)
        except Exception as exc:  # said by start() or on the log, never a silent stop
            self.error = exc
            self._ready.set()
            log.error("goal histories of run %s: stopped: %s", self.run, exc)

    def _take(self, batch: list[tuple[str, bytes]]) -> int:
        for key, payload in batch:
            try:
                record: dict[str, Any] = to_record(key, payload)
                self.history.feed(record)
            except (CodecError, AttributeError, KeyError, TypeError, ValueError,
                    RecursionError) as exc:
                log.warning("goal history: not taken: %s", exc)
        return len(batch)
