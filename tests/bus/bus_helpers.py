"""Helpers for the bus tests: start pass-through stages as real subprocesses (never forked)
and read back which cycles each one computed."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

from bus.config import BusConfig
from bus.passthrough import STAGES

ROOT = Path(__file__).resolve().parents[2]
AGENT = "A"
PIPELINE = [f"{AGENT}.{s}" for s in STAGES]


def pipeline(agent: str) -> list[str]:
    return [f"{agent}.{s}" for s in STAGES]


def python(*args: str, **popen: object) -> subprocess.Popen:
    """Start `python ARGS` from the repository root (a fresh interpreter: never a fork)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.Popen([sys.executable, *args], cwd=ROOT, env=env, **popen)


class Stages:
    """Pass-through stage processes, each logging the cycles it computes; keyed by process
    name ("A.inference")."""

    def __init__(self, cfg: BusConfig, run: str, tmp: Path) -> None:
        self.cfg, self.run, self.tmp = cfg, run, tmp
        self.procs: dict[str, subprocess.Popen] = {}

    def log(self, process: str) -> Path:
        return self.tmp / f"{process}.log"

    def cycles(self, process: str) -> list[int]:
        path = self.log(process)
        return [int(x) for x in path.read_text().split()] if path.exists() else []

    def start(self, stage: str, *extra: str, agent: str = AGENT) -> subprocess.Popen:
        process = f"{agent}.{stage}"
        proc = python("-m", "bus.passthrough", "--run", self.run, "--agent", agent,
                      "--stage", stage, "--log", str(self.log(process)), *extra,
                      *self.cfg.to_args())
        self.procs[process] = proc
        return proc

    def start_agent(self, agent: str = AGENT, **extra: tuple[str, ...]) -> None:
        for stage in STAGES:
            self.start(stage, *extra.get(stage, ()), agent=agent)

    def stop_all(self) -> None:
        for proc in self.procs.values():
            if proc.poll() is None:
                proc.send_signal(signal.SIGCONT)
                proc.terminate()
        for proc in self.procs.values():
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait(10)
