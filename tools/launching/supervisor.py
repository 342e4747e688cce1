"""Child processes of `teleo launch`: start, watch, restart per policy, stop quickly.

Like `ros2 launch` with `respawn=True`: a process that exits while the run goes on is started
again with the same command (plus its `restart_args`, e.g. the world's `--resume`), at most
`max_restarts` times. Children are started with subprocess (fork + exec at once), never by
forking a Python process that has a zenoh session (docs/bus.md, "Zenoh in Python", item 2).
Each child's output goes to its own log file, and each is told the launcher's pid
(TELEO_PARENT_PID) so it
exits when the launcher dies (bus/lifeline.py).

Stopping is bounded (docs/faults.md: Ctrl-C stops a run within 2 s in any state): the `first`
group (the world, the clock) is asked to stop (SIGTERM) and given up to `first_s`, then every
other process at once, then the `last` group (the router); whatever is still there after its
share of time (a hung process) is killed, and a stopped (SIGSTOPped) one is killed at once:
the stop never waits on it.
"""

from __future__ import annotations

import logging
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path

from bus.lifeline import ENV_PARENT, ENV_PROFILE

log = logging.getLogger(__name__)
PROFILE_GRACE_S = 10.0  # [s] more time to stop when each process saves a profile (TELEO_PROFILE)


@dataclass(frozen=True)
class ProcSpec:
    """How to start one process: its name (the liveliness name, e.g. "ME.inference"), its
    command, how often it may be restarted, extra arguments on a restart, extra environment."""

    name: str
    argv: tuple[str, ...]
    max_restarts: int = 3
    env: dict[str, str] = field(default_factory=dict)
    restart_args: tuple[str, ...] = ()


@dataclass
class _Child:
    spec: ProcSpec
    popen: subprocess.Popen
    restarts: int = 0
    exits: list[int] = field(default_factory=list)
    gave_up: bool = False


@dataclass(frozen=True)
class Exit:
    """A child that exited by itself: restarted (True) or left down (False); `at`: when it
    was seen gone [s, time.monotonic()]."""

    name: str
    returncode: int
    restarted: bool
    restarts: int
    at: float = 0.0


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
        self._children[spec.name] = _Child(spec, self._spawn(spec, spec.argv))

    def adopt(self, spec: ProcSpec, popen: subprocess.Popen) -> None:
        """Supervise a process started elsewhere (the router: started first, to learn its
        port); restarts use `spec.argv`."""
        self._children[spec.name] = _Child(spec, popen)

    def _spawn(self, spec: ProcSpec, argv: tuple[str, ...]) -> subprocess.Popen:
        out = open(self.log_dir / f"{spec.name}.log", "ab")  # noqa: SIM115 (inherited)
        env = {**os.environ, **spec.env, ENV_PARENT: str(os.getpid())}
        if env.get(ENV_PROFILE):   # a child may run in another folder
            env[ENV_PROFILE] = os.path.abspath(env[ENV_PROFILE])
        try:
            return subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT,
                                    stdin=subprocess.DEVNULL, cwd=self.cwd, env=env,
                                    start_new_session=True)
        finally:
            out.close()

    def names(self) -> list[str]:
        return list(self._children)

    def pid(self, name: str) -> int:
        return self._children[name].popen.pid

    def pids(self) -> dict[str, int]:
        return {name: c.popen.pid for name, c in self._children.items()}

    def running(self, name: str) -> bool:
        return self._children[name].popen.poll() is None

    def restarts(self) -> dict[str, int]:
        return {name: c.restarts for name, c in self._children.items()}

    def left_down(self) -> list[str]:
        """Processes that exited and were not restarted (policy exhausted or exempt)."""
        return [name for name, c in self._children.items()
                if c.gave_up and c.popen.poll() is not None]

    def poll(self, exempt: tuple[str, ...] = (),
             restartable: Callable[[str, int], bool] | None = None) -> list[Exit]:
        """Restart children that exited (per their policy); `exempt` ones are only reported;
        `restartable(name, returncode)` may refuse a restart (e.g. a world that cannot
        resume)."""
        exits: list[Exit] = []
        for name, child in self._children.items():
            rc = child.popen.poll()
            if rc is None or child.gave_up:
                continue
            now = time.monotonic()
            child.exits.append(rc)
            refused = restartable is not None and not restartable(name, rc)
            if name in exempt or refused or child.restarts >= child.spec.max_restarts:
                child.gave_up = True
                exits.append(Exit(name, rc, False, child.restarts, now))
                continue
            child.restarts += 1
            log.warning("%s exited with %s; restart %d of %d", name, rc, child.restarts,
                        child.spec.max_restarts)
            child.popen = self._spawn(child.spec, child.spec.argv + child.spec.restart_args)
            exits.append(Exit(name, rc, True, child.restarts, now))
        return exits

    def stop(self, names: list[str], timeout: float = 5.0) -> dict[str, int | None]:
        """Stop `names` one after the other: SIGTERM, then SIGKILL after `timeout` [s]."""
        codes: dict[str, int | None] = {}
        for name in names:
            codes.update(self._stop_group([name], timeout))
        return codes

    def stop_all(self, first: list[str], last: Iterable[str] = (), first_s: float = 0.8,
                 rest_s: float = 1.0, last_s: float = 0.2,
                 keep: Iterable[str] = ()) -> dict[str, int | None]:
        """Stop `first` (in order, `first_s` [s] in all), then every other process at once
        (`rest_s`), then `last` (`last_s`), leaving `keep` running; each group's stragglers
        are killed. The other processes get the largest share: the goal-entry process saves
        its last statuses and every process closes its zenoh session, which takes long on a
        busy machine."""
        last = [n for n in last if n in self._children]
        rest = [n for n in reversed(self._children)
                if n not in first and n not in last and n not in keep]
        codes = self._stop_group([n for n in first if n in self._children], first_s)
        codes.update(self._stop_group(rest, rest_s))
        codes.update(self._stop_group(last, last_s, quiet=True))
        return codes

    def _stop_group(self, names: list[str], timeout: float,
                    quiet: bool = False) -> dict[str, int | None]:
        children = [(n, self._children[n]) for n in names if n in self._children]
        for name, child in children:
            child.gave_up = True
            if stopped(child.popen.pid):  # SIGSTOPped: it has nothing to finish, so the stop
                log.info("%s (pid %d) is stopped: killed", name, child.popen.pid)  # waits
                _signal(child.popen, signal.SIGKILL)  # for none of it
                continue
            # SIGTERM, not SIGINT: one still importing its modules, which has no handler
            # yet, ends quietly (SIGINT made Python print a KeyboardInterrupt traceback)
            _signal(child.popen, signal.SIGTERM)
        if os.environ.get(ENV_PROFILE):
            timeout += PROFILE_GRACE_S   # writing a profile takes a while on a busy machine
        end = time.monotonic() + timeout
        codes: dict[str, int | None] = {}
        for name, child in children:
            try:
                codes[name] = child.popen.wait(max(0.0, end - time.monotonic()))
            except subprocess.TimeoutExpired:
                (log.info if quiet else log.warning)(
                    "%s (pid %d) still running %.1f s after SIGTERM: killed", name,
                    child.popen.pid, timeout)
                _signal(child.popen, signal.SIGKILL)
                codes[name] = child.popen.wait()
        return codes


def stopped(pid: int) -> bool:
    """Whether process `pid` is stopped (SIGSTOP, or a debugger's): state T or t."""
    try:
        stat = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return False
    return stat.rsplit(")", 1)[-1].split()[0] in ("T", "t")


def _signal(popen: subprocess.Popen, sig: signal.Signals) -> None:
    if popen.poll() is None:
        try:
            popen.send_signal(sig)
        except ProcessLookupError:
            pass


def wait_until(predicate: Callable[[], object], timeout: float, interval: float = 0.05) -> bool:
    """Poll `predicate()` until true or `timeout` [s] passes; returns the last value."""
    end = time.monotonic() + timeout
    while True:
        if predicate():
            return True
        if time.monotonic() >= end:
            return False
        time.sleep(interval)
