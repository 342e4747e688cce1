"""The harness of bench/faults/drills.py: one real `teleo launch` in the background, in a run folder
of its own, with what a drill reads of it (the registry entry, the trace, the journal, the
summary), and waiting for it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
TELEO = str(Path(sys.executable).parent / "teleo")
DEMO = ROOT / "scenarios" / "driving_demo.toml"


EXTRA: list[str] = []  # flags given to every launch (--secure)


class Launch:
    """One `teleo launch` in the background, with its own run folder (`runs_in`: its
    TELEO_RUN_DIR, when not `folder`, where its summary and output go)."""

    def __init__(self, folder: Path, scenario: Path, *args: str,
                 runs_in: Path | None = None, preexec_fn=None) -> None:
        args = (*args, *(a for a in EXTRA if a not in args))
        self.folder = folder
        self.state = runs_in or folder
        self.env = {**os.environ, "TELEO_RUN_DIR": str(self.state)}
        self.out = (folder / "launch.out").open("w")
        self._info: dict[str, Any] | None = None
        self.proc = subprocess.Popen(
            [TELEO, "launch", str(scenario), "--summary", str(folder / "summary.json"), *args],
            cwd=ROOT, env=self.env, stdout=self.out, stderr=subprocess.STDOUT,
            preexec_fn=preexec_fn)  # noqa: PLW1509 (the drill has no threads then)

    def info(self, timeout: float = 120.0) -> dict[str, Any]:
        """The run file, once the launcher has registered the run (every process up); the
        pids are re-read while the run is registered (restarts change them)."""
        files = list((self.state / "active").glob("*.json"))
        if files:
            self._info = json.loads(files[0].read_text())
        if self._info is not None:
            return self._info
        found = wait_for(lambda: list((self.state / "active").glob("*.json"))
                         or self.proc.poll() is not None, timeout)
        files = list((self.state / "active").glob("*.json"))
        if not found or not files:
            raise RuntimeError(f"the launch did not register its run:\n{self.output()}")
        self._info = json.loads(files[0].read_text())
        return self._info

    def run_dir(self) -> Path:
        return Path(self.info()["run_dir"])

    def cycles(self) -> int:
        """Complete lines in the trace so far."""
        path = self.run_dir() / "trace.jsonl"
        return path.read_bytes().count(b"\n") if path.exists() else 0

    def wait_cycle(self, n: int, timeout: float = 120.0) -> bool:
        return wait_for(lambda: self.cycles() >= n or self.proc.poll() is not None, timeout)

    def journal(self) -> list[dict[str, Any]]:
        path = self.run_dir() / "supervision.jsonl"
        return [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []

    def pid(self, name: str) -> int:
        return int(self.info()["pids"][name])

    def finish(self, timeout: float = 300.0) -> int:
        try:
            return self.proc.wait(timeout)
        finally:
            self.out.close()

    def summary(self) -> dict[str, Any]:
        path = self.folder / "summary.json"
        return json.loads(path.read_text()) if path.exists() else {}

    def output(self) -> str:
        if not self.out.closed:
            self.out.flush()
        return (self.folder / "launch.out").read_text()

    def trace(self) -> str:
        return (self.run_dir() / "trace.jsonl").read_text()


def wait_for(predicate, timeout: float, interval: float = 0.02) -> bool:
    end = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > end:
            return False
        time.sleep(interval)
    return True


@dataclass(frozen=True)
class Reference:
    """An undisturbed launch of a scenario: its trace and its summary."""

    trace: str
    summary: dict[str, Any]


def reference(scenario: Path, folder: Path, *args: str) -> Reference:
    """The trace and summary of an undisturbed launch of `scenario`."""
    run = Launch(folder, scenario, *args)
    run.info()
    rc = run.finish()
    if rc != 0:
        raise RuntimeError(f"reference launch failed ({rc}):\n{run.output()}")
    return Reference(run.trace(), run.summary())


def pids_alive(pids: list[int]) -> list[int]:
    out = []
    for pid in pids:
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            continue
        if stat.rsplit(")", 1)[-1].split()[0] not in ("Z", "X"):
            out.append(pid)
    return out
