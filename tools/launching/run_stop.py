"""How a launch stops its run (tools/launching/supervision.py), in order and quickly, whatever point
its start had reached: the world first (so that no cycle runs while a stage goes), then every
other process, the record's last messages, the router, the launcher's own session and its
registry entry. A second stop signal never breaks this off (tools/launching/stop_signals.py); it
only cuts the record's drain short. Each part's time goes in the run's journal, supervision.jsonl.
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Callable
from contextlib import ExitStack
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import click

from tools.launching.run_plan import Plan
from tools.launching.supervisor import Supervisor
from tools.runs import runfile
from world.recorder import TRACE

log = logging.getLogger(__name__)
DRAIN_TIMEOUT_S = 40.0  # [s] the longest the record's drain may hold a stop (`teleo stop`
                        # waits 60 s for the launcher)
DRAIN_QUIET_S, DRAIN_EVERY_S = 1.0, 3.0  # [s] a drain says nothing for as long, then so often


@dataclass
class Outcome:
    """How the launch ended: restarts per process, processes left down, the launcher's reason
    for ending the run early, whether a user asked for the stop, the recorder's report
    (BusRecorder.report) and how long each part of the stop took [s]."""

    restarts: dict[str, int] = field(default_factory=dict)
    left_down: tuple[str, ...] = ()
    ended: str = ""
    requested_stop: bool = False
    recorder: dict[str, Any] = field(default_factory=dict)
    stop_s: dict[str, float] = field(default_factory=dict)


class Journal:
    """supervision.jsonl: what the launcher saw, with wall-clock times [s]. A journal that
    cannot be written (a full disk) says so once on the log and stops: the run goes on."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.broken = False

    def write(self, event: str, **fields: Any) -> None:
        if self.broken:
            return
        line = json.dumps({"t": round(time.time(), 4), "event": event, **fields})
        try:
            with self.path.open("a") as f:
                f.write(line + "\n")
        except OSError as exc:
            self.broken = True
            log.warning("%s cannot be written (%s): it ends here", self.path, exc.strerror)


@dataclass
class Held:
    """What the stop must undo, whatever point the start had reached (a signal can come at
    any moment of it): the registry entry, the recorder, the launcher's own bus session."""

    info: runfile.RunInfo | None = None
    recorder: Any = None  # tools.records.recorder.BusRecorder
    goal_watch: Any = None  # tools.records.goal_watch.GoalWatch (a launch with no record)
    session: ExitStack = field(default_factory=ExitStack)

    def cut_short(self) -> None:
        """A second stop signal: stop waiting for the record's last messages."""
        if self.recorder is not None:
            self.recorder.cut_short()


def stop_run(plan: Plan, sup: Supervisor, journal: Journal, outcome: Outcome,
             held: Held) -> None:
    """Stop everything quickly, in order: the world (so that no cycle runs while a stage
    goes), every other process, the record's last messages, the router; then the launcher's
    own session and its registry entry. Each part's time goes in the journal."""
    marks = [time.monotonic()]

    def lap(name: str) -> None:
        marks.append(time.monotonic())
        outcome.stop_s[name] = round(marks[-1] - marks[-2], 3)

    journal.write("stopping", requested=outcome.requested_stop, ended=outcome.ended)
    sup.stop_all(["world"], keep=["router"])
    lap("processes")
    if held.recorder is not None:  # drained while the router still holds what it is owed
        held.recorder.stop(timeout=DRAIN_TIMEOUT_S, progress=drain_progress(plan.run_dir),
                           until=trace_cycles(plan.run_dir) if plan.runs_world else None)
        outcome.recorder = held.recorder.report()
        lap("record")
    if held.goal_watch is not None:
        held.goal_watch.stop()
        lap("goal histories")
    sup.stop_all([], last=["router"])
    lap("router")
    held.session.close()
    if held.info is not None:
        runfile.remove(held.info)
    lap("session")
    journal.write("stopped", seconds=round(marks[-1] - marks[0], 3), **outcome.stop_s)


def drain_progress(run_dir: Path) -> Callable[[Any, float], None]:
    """What the launcher says while its record takes the last messages (a loaded machine
    can leave it thousands of cycles behind the run): from DRAIN_QUIET_S on, a line every
    few seconds with the cycle reached, and how to stop waiting."""
    said = [0.0]
    ran = trace_cycles(run_dir)

    def show(recorder, seconds: float) -> None:
        if seconds < DRAIN_QUIET_S or (said[0] and seconds - said[0] < DRAIN_EVERY_S):
            return
        said[0] = seconds
        at = recorder.last_cycle if recorder.last_cycle is not None else -1
        click.echo(f"record: still writing what the run sent before its stop, cycle {at} of "
                   f"{ran - 1} ({seconds:.0f} s; Ctrl-C again leaves the rest out)", err=True)

    return show


def trace_cycles(run_dir: Path) -> int:
    """The cycles the world has run: the complete lines of its trace."""
    try:
        with (run_dir / TRACE).open("rb") as f:
            return sum(chunk.count(b"\n") for chunk in iter(lambda: f.read(1 << 20), b""))
    except OSError:
        return 0
