"""The files a world process keeps in its run folder (docs/faults.md, "What a run records").

trace.jsonl      one line per cycle run: the actions applied to each agent (its own, or the
                 world's safe action when they did not arrive), the counters, a digest of the
                 state, the outcomes of injected events and each agent memory that changed.
                 Nothing that depends on timing, so two lockstep runs with one seed give the
                 same file; it is also what a restarted world replays.
health.jsonl     what did depend on timing: every cycle that was not clean (agents given the
                 safe action, late, dead or stalled stages, re-sent states, how long it took),
                 each start of the world (and from which cycle it resumed), a progress line
                 about once a second, and the end. The run's summary is built from it, so it
                 stays true when the world is killed.
snapshots.jsonl  every `render_every`-th snapshot and the last (for rendering)
checkpoint.pkl   the simulation every CHECKPOINT_EVERY cycles (World.checkpoint), so a
                 restarted world replays at most that many cycles
world-final.json the totals of a world that ended by itself or by a signal

Lines are written whole and flushed at once; a process killed mid-line leaves a partial last
line, which `complete_lines` ignores and `truncate_partial` removes before appending.

A file that cannot be written (a full disk, docs/faults.md): the trace and the health record
are the run's own record, which the summary and a restart read, so a failed write of either
raises CannotRecord and the world stops the run; the snapshots (pictures only) and the
checkpoint (a shorter replay after a restart) are given up from that cycle on, said on the
log and in world-final.json's "lost", and the run goes on.
"""

from __future__ import annotations

import json
import logging
import os
import pickle
import time
from collections import Counter
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any, Protocol, TextIO

from world.errors import CannotRecord
from world.trace import digest, trace_line

TRACE, HEALTH, SNAPSHOTS = "trace.jsonl", "health.jsonl", "snapshots.jsonl"
CHECKPOINT, WORLD_FINAL = "checkpoint.pkl", "world-final.json"
log = logging.getLogger("teleo.world")
CHECKPOINT_EVERY = 100   # [cycles]
PROGRESS_EVERY_S = 1.0   # [s] between progress lines in health.jsonl


class CycleReport(Protocol):
    """What the recorder reads of the clock's report of a cycle (bus.cycle.CycleReport; the
    world reaches the bus only through world/process.py)."""

    noop: Sequence[str]
    late: Sequence[str]
    dead: Sequence[str]
    stalled: Sequence[str]
    republished: int
    elapsed_ms: float
    stage_ms: Mapping[str, float]
    clean: bool


def complete_lines(path: Path) -> list[str]:
    """The whole lines of a JSON-lines file (a partial last line is left out)."""
    return [line.decode(errors="replace") for line in complete_lines_bytes(path)]


def complete_lines_bytes(path: Path) -> list[bytes]:
    """`complete_lines` as bytes, not decoded (for a reader that looks at few of them)."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return []
    end = data.rfind(b"\n")
    return data[:end].split(b"\n") if end >= 0 else []


def truncate_partial(path: Path) -> None:
    """Cut a partial last line off `path` (left by a process killed while writing it)."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return
    end = data.rfind(b"\n") + 1
    if end != len(data):
        with path.open("r+b") as f:
            f.truncate(end)


def read_jsonl(path: Path) -> list[dict[str, Any]]:
    """The JSON objects of the complete lines of `path` (unreadable lines skipped)."""
    out = []
    for line in complete_lines(path):
        try:
            doc = json.loads(line)
        except ValueError:
            continue
        if isinstance(doc, dict):
            out.append(doc)
    return out


class Recorder:
    """Writes the run folder's files (see the module doc) for one world process."""

    def __init__(self, out: Path, render_every: int, resumed_at: int = 0) -> None:
        self.out = out
        self.render_every = render_every
        mode = "a" if resumed_at else "w"
        try:
            out.mkdir(parents=True, exist_ok=True)
            for name in (TRACE, SNAPSHOTS, HEALTH):
                if resumed_at:
                    truncate_partial(out / name)
            self.trace: TextIO = (out / TRACE).open(mode, buffering=1)  # whole lines
            self.snaps: TextIO = (out / SNAPSHOTS).open(mode)
            self.health: TextIO = (out / HEALTH).open("a" if resumed_at else "w", buffering=1)
        except OSError as exc:
            raise CannotRecord(f"{exc.filename or out}: cannot be opened for writing "
                               f"({exc.strerror or exc})") from exc
        self.totals = {k: Counter() for k in ("late", "dead", "noop", "stalled")}
        self.stage_ms: Counter[str] = Counter()
        self.cycle_ms = self.world_ms = 0.0
        self.cycles = resumed_at
        self.last_snapshot: dict[str, Any] | None = None
        self._prepared: tuple[int, Any, str, str] = (-1, None, "", "")
        self.last_written = -1
        self._progress_at = 0.0
        self.lost: dict[str, dict[str, Any]] = {}  # file -> {"cycle", "reason"}: given up
        if resumed_at:
            self._reload_totals()

    def _record(self, f: TextIO, text: str, cycle: int) -> None:
        """Write one whole line of the trace or the health record, or raise CannotRecord."""
        try:
            f.write(text)
        except OSError as exc:
            raise CannotRecord(f"{Path(f.name).name}: cycle {cycle} cannot be written "
                               f"({exc.strerror or exc})") from exc

    def _give_up(self, name: str, cycle: int, exc: OSError) -> None:
        """A file the run can do without could not be written: not again from here on."""
        if name not in self.lost:
            self.lost[name] = {"cycle": cycle, "reason": exc.strerror or str(exc)}
            log.error("%s: not written from cycle %d on (%s); the run goes on without it",
                      self.out / name, cycle, exc.strerror or exc)

    def _reload_totals(self) -> None:
        for doc in read_jsonl(self.out / HEALTH):
            if doc.get("kind") == "cycle":
                for k, counter in self.totals.items():
                    counter.update(doc.get(k, ()))

    def event(self, kind: str, **fields: Any) -> None:
        """A health line: start, resume, end, progress, ... with the wall time [s]."""
        line = {"kind": kind, "t": round(time.time(), 3), **fields}
        self._record(self.health, json.dumps(line, sort_keys=True) + "\n",
                     int(fields.get("cycle", self.cycles)))

    def prepare(self, t: int, snap: dict[str, Any]) -> None:
        """Make what cycle `t`'s record needs of its state alone (its digest, and its line
        in snapshots.jsonl when one is kept) while the agents work on that state (the world
        calls it through Clock.run_cycle's `meanwhile`), so `cycle` writes at once."""
        self._prepared = (t, snap, digest(snap),
                          json.dumps(snap) + "\n" if t % self.render_every == 0 else "")

    def cycle(self, t: int, snap: dict[str, Any], applied: dict[str, list],
              injected: list[dict[str, Any]], report: CycleReport, world_ms: float,
              memory: dict[str, Any] | None = None,
              control: dict[str, Any] | None = None) -> None:
        """Record cycle `t`: its trace line, a health line if it was not clean, totals.
        `memory`: the agents whose memory changed this cycle, with the new one; `control`:
        what changed at its start (world/changes.py)."""
        ready = self._prepared if self._prepared[0] == t and self._prepared[1] is snap \
            else (t, snap, "", "")
        self._record(self.trace, trace_line(t, snap, applied, injected, memory, ready[2],
                                            control), t)
        self.cycles = t + 1
        if not report.clean or report.stalled or report.republished:
            self.event("cycle", cycle=t, noop=list(report.noop), late=list(report.late),
                       dead=list(report.dead), stalled=list(report.stalled),
                       republished=report.republished,
                       elapsed_s=round(report.elapsed_ms / 1e3, 3))
        for k, names in (("late", report.late), ("dead", report.dead), ("noop", report.noop),
                         ("stalled", report.stalled)):
            self.totals[k].update(names)
        self.stage_ms.update(report.stage_ms)
        self.cycle_ms += report.elapsed_ms
        self.world_ms += world_ms
        self.last_snapshot = snap
        if t % self.render_every == 0:
            self._snapshot(t, snap, ready[3])
        now = time.monotonic()
        if now - self._progress_at >= PROGRESS_EVERY_S:
            self._progress_at = now
            self.event("progress", cycle=t)

    def _snapshot(self, t: int, snap: dict[str, Any], line: str = "") -> None:
        if SNAPSHOTS in self.lost:
            return
        try:
            self.snaps.write(line or json.dumps(snap) + "\n")
            self.last_written = t
        except OSError as exc:
            self._give_up(SNAPSHOTS, t, exc)

    def checkpoint(self, next_cycle: int, blob: bytes, outcomes: dict[str, list]) -> None:
        """Save the simulation as it is before cycle `next_cycle` (atomic replace; one that
        cannot be written leaves the last one as it was, and none is tried again)."""
        if CHECKPOINT in self.lost:
            return
        tmp = self.out / (CHECKPOINT + ".tmp")
        try:
            with tmp.open("wb") as f:
                pickle.dump({"version": 1, "cycle": next_cycle, "world": blob,
                             "outcomes": outcomes}, f)
            os.replace(tmp, self.out / CHECKPOINT)
        except OSError as exc:
            tmp.unlink(missing_ok=True)  # its own half-written file: the room it took back
            self._give_up(CHECKPOINT, next_cycle, exc)

    def finish(self, completed: bool, elapsed_s: float, reason: str,
               memory: dict[str, Any] | None = None) -> None:
        """Close the files and write world-final.json (totals of the whole run, each agent's
        last memory, and what was given up: "lost"); on a full disk as much of it as can be
        written (never raises)."""
        if self.last_snapshot is not None and self.last_written != self.cycles - 1:
            self._snapshot(self.cycles - 1, self.last_snapshot)
        try:
            self.event("end", cycle=self.cycles, completed=completed, reason=reason,
                       **({"lost": self.lost} if self.lost else {}))
        except CannotRecord as exc:
            log.error("%s", exc)
        for f in (self.trace, self.snaps, self.health):
            try:
                f.close()
            except OSError as exc:  # what it still held could not be written
                log.error("%s: not closed whole (%s)", f.name, exc.strerror or exc)
        final = {
            "completed": completed, "cycles": self.cycles, "elapsed_s": elapsed_s,
            "reason": reason, **{k: dict(v) for k, v in self.totals.items()},
            "counters": (self.last_snapshot or {}).get("counters", {}),
            "timing_ms": {"cycle": self.cycle_ms, "world": self.world_ms,
                          "stages": dict(self.stage_ms)},
            "memory": memory or {},
            "lost": self.lost,
            **({"episode": self.last_snapshot["episode"]}   # an episodic world's (gymnasium)
               if "episode" in (self.last_snapshot or {}) else {}),
        }
        tmp = self.out / (WORLD_FINAL + ".tmp")
        try:
            tmp.write_text(json.dumps(final, indent=1))
            tmp.replace(self.out / WORLD_FINAL)
        except OSError as exc:
            tmp.unlink(missing_ok=True)
            log.error("%s: not written (%s)", self.out / WORLD_FINAL, exc.strerror or exc)
