"""Helpers for the end-to-end tests: real `teleo` commands in real subprocesses, each test
with its own run folder ($TELEO_RUN_DIR), so tests never see each other's launches."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = Path(__file__).resolve().parent / "fixtures"
HOLD_SPEED = FIXTURES / "hold_speed.toml"
PARKED = FIXTURES / "parked.toml"   # a standing car whose one law always holds
TELEO = (str(Path(sys.executable).parent / "teleo"),)


class Teleo:
    """Runs `teleo ...` with TELEO_RUN_DIR set to one folder."""

    def __init__(self, run_dir: Path) -> None:
        self.run_dir = run_dir
        self.env = {**os.environ, "TELEO_RUN_DIR": str(run_dir)}
        self.launcher: subprocess.Popen | None = None

    def __call__(self, *args: str, timeout: float = 60) -> subprocess.CompletedProcess:
        return subprocess.run([*TELEO, *args], cwd=ROOT, env=self.env, capture_output=True,
                              text=True, timeout=timeout)

    def start(self, *args: str) -> subprocess.Popen:
        """`teleo ...` in the background (stdout/stderr to launch.out in the run folder)."""
        with open(self.run_dir / "launch.out", "w") as out:
            self.launcher = subprocess.Popen([*TELEO, *args], cwd=ROOT, env=self.env,
                                             stdout=out, stderr=subprocess.STDOUT, text=True)
        return self.launcher

    def run_files(self) -> list[Path]:
        """The run registry's files in this folder (tools/runs/runfile.py): one per running run."""
        return sorted((self.run_dir / "active").glob("*.json"))

    def run_info(self, timeout: float = 60) -> dict:
        """The run file of the running launch, once it has been written (all announced)."""
        launcher = self.launcher

        def running() -> bool:
            return launcher is None or launcher.poll() is None
        assert wait_for(lambda: self.run_files() or not running(), timeout), \
            self.launch_output()
        files = self.run_files()
        assert files, f"the launch ended:\n{self.launch_output()}"
        return json.loads(files[0].read_text())

    def launch_output(self) -> str:
        path = self.run_dir / "launch.out"
        return path.read_text() if path.exists() else ""


def wait_for(predicate, timeout: float) -> bool:
    """Poll `predicate` until true or `timeout` [s] (bounded waits on real events)."""
    end = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > end:
            return False
        time.sleep(0.05)
    return True


def trace_lines(info: dict) -> int:
    path = Path(info["run_dir"]) / "trace.jsonl"
    return len(path.read_text().splitlines()) if path.exists() else 0


def interrupt(proc: subprocess.Popen, timeout: float = 60) -> int | str:
    """Ctrl-C the launcher and wait for it to stop everything; its exit status, or a
    sentence when it was still running after `timeout` [s] (then killed), so the caller's
    assertion message (the launch's output) is what a failure shows."""
    proc.send_signal(signal.SIGINT)
    try:
        return proc.wait(timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        return f"still running {timeout:g} s after SIGINT (killed)"


def two_cars(tmp_path: Path, cycles: int = 25) -> str:
    """A scenario of two cars, A1 and A2, holding their speed with ONE program that names no
    agent (``?self``); its path."""
    program = (FIXTURES / "hold_speed.tlp").read_text().replace(
        "(goals (at-desired-speed ME))", "(goals (at-desired-speed ?self))")
    (tmp_path / "any_car.tlp").write_text(program)
    cars = ('cars = [{ agent = "A1", street = "B", from = "FIRST", toward = "SECOND" }, '
            '{ agent = "A2", street = "SECOND", from = "A", toward = "B" }]')
    text = "\n".join([
        "[run]", 'name = "two-cars"', 'mode = "lockstep"', f"cycles = {cycles}", "seed = 4", "",
        "[world]", "grid = [3, 3]", "pedestrians = 2", "traffic = 0", cars, "",
        *(f'[[agents]]\nid = "{a}"\nprogram = "any_car.tlp"\nsolver = false\n'
          for a in ("A1", "A2"))])
    path = tmp_path / "two_cars.toml"
    path.write_text(text)
    return str(path)
