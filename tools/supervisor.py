"""Child processes of `teleo launch`: start, watch, restart per policy, stop in order.

Like `ros2 launch` with `respawn=True`: a process that exits while the run goes on is started
again with the same command, at most `max_restarts` times. Children are started with
subprocess (fork + exec at once), never by forking a Python process that has a zenoh session
(notes/zenoh.md, pitfall 2). Each child's output goes to its own log file.
"""

from __future__ import annotations

import logging
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class ProcSpec:
    """How to start one process: its name (the liveliness name, e.g. "ME.inference")."""

    name: str
    argv: tuple[str, ...]
    max_restarts: int = 3
    env: dict[str, str] = field(default_factory=dict)


@dataclass
class _Child:
    spec: ProcSpec
    popen: subprocess.Popen
    restarts: int = 0
    exits: list[int] = field(default_factory=list)
    gave_up: bool = False


@dataclass(frozen=True)
class Exit:
    """A child that exited by itself: restarted (True) or left down (False)."""

    name: str
    returncode: int
    restarted: bool
    restarts: int


def module_argv(module: str, *args: str) -> tuple[str, ...]:
    """The command that runs `python -m module args` with this interpreter."""
    return (sys.executable, "-m", module, *args)


class Supervisor:
    """Owns the children of one launch; not thread-safe (the launcher's loop drives it)."""

    def __init__(self, log_dir: Path, cwd: Path | None = None) -> None:
        self.log_dir = log_dir
        self.cwd = cwd
        self._children: dict[str, _Child] = {}
        log_dir.mkdir(parents=True, exist_ok=True)

    def start(self, spec: ProcSpec) -> None:
        """Start `spec` (it must not be running yet)."""
        if spec.name in self._children:
            raise ValueError(f"process {spec.name!r} already started")
        self._children[spec.name] = _Child(spec, self._spawn(spec))

    def _spawn(self, spec: ProcSpec) -> subprocess.Popen:
        out = open(self.log_dir / f"{spec.name}.log", "ab")  # the child inherits it
        try:
            return subprocess.Popen(spec.argv, stdout=out, stderr=subprocess.STDOUT,
                                    stdin=subprocess.DEVNULL, cwd=self.cwd,
                                    env={**os.environ, **spec.env}, start_new_session=True)
        finally:
            out.close()

    def names(self) -> list[str]:
        return list(self._children)

    def pid(self, name: str) -> int:
        return self._children[name].popen.pid

    def running(self, name: str) -> bool:
        return self._children[name].popen.poll() is None

    def restarts(self) -> dict[str, int]:
        return {name: c.restarts for name, c in self._children.items()}

    def poll(self, exempt: tuple[str, ...] = ()) -> list[Exit]:
        """Restart children that exited (per their policy); `exempt` ones are only reported."""
        exits: list[Exit] = []
        for name, child in self._children.items():
            rc = child.popen.poll()
            if rc is None or child.gave_up:
                continue
            child.exits.append(rc)
            if name in exempt or child.restarts >= child.spec.max_restarts:
                child.gave_up = True
                exits.append(Exit(name, rc, False, child.restarts))
                continue
            child.restarts += 1
            log.warning("%s exited with %s; restart %d of %d", name, rc, child.restarts,
                        child.spec.max_restarts)
            child.popen = self._spawn(child.spec)
            exits.append(Exit(name, rc, True, child.restarts))
        return exits

    def stop(self, names: list[str], timeout: float = 5.0) -> dict[str, int | None]:
        """Stop `names` in order: SIGINT, then SIGTERM, then SIGKILL after `timeout` [s] each."""
        codes: dict[str, int | None] = {}
        for name in names:
            child = self._children.get(name)
            if child is None:
                continue
            child.gave_up = True
            codes[name] = _stop_one(child.popen, timeout)
        return codes

    def stop_all(self, first: list[str], timeout: float = 5.0) -> dict[str, int | None]:
        """Stop `first` in that order, then everything else in reverse start order."""
        rest = [n for n in reversed(self._children) if n not in first]
        return self.stop(first + rest, timeout)


def _stop_one(popen: subprocess.Popen, timeout: float) -> int | None:
    for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL):
        if popen.poll() is not None:
            return popen.returncode
        try:
            popen.send_signal(sig)
        except ProcessLookupError:
            break
        try:
            return popen.wait(timeout)
        except subprocess.TimeoutExpired:
            log.warning("pid %d ignored %s", popen.pid, sig.name)
    return popen.poll()


def wait_until(predicate, timeout: float, interval: float = 0.05) -> bool:
    """Poll `predicate()` until true or `timeout` [s] passes; returns the last value."""
    end = time.monotonic() + timeout
    while True:
        if predicate():
            return True
        if time.monotonic() >= end:
            return False
        time.sleep(interval)
