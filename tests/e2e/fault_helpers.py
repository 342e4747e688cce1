"""Helpers for the fault tests: scenario variants, the run's journal, signals, pids."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path

from e2e_helpers import FIXTURES, HOLD_SPEED, Teleo, wait_for


def scenario(folder: Path, name: str = "hold.toml", **run: object) -> Path:
    """hold_speed.toml with its program path made absolute, and [run] or [[agents]] values
    changed: respawn={...} goes to the agent, anything else to [run]."""
    text = HOLD_SPEED.read_text().replace('program = "hold_speed.tlp"',
                                          f'program = "{FIXTURES / "hold_speed.tlp"}"')
    respawn = run.pop("respawn", None)
    if respawn is not None:
        pairs = ", ".join(f"{k} = {v}" for k, v in respawn.items())
        text = text.replace("respawn = { perception = 2, inference = 2, executive = 2 }",
                            f"respawn = {{ {pairs} }}")
    for key, value in run.items():
        text = text.replace("[run]\n", f"[run]\n{key} = {json.dumps(value)}\n", 1)
    path = folder / name
    path.write_text(text)
    return path


def trace(info: dict) -> str:
    return (Path(info["run_dir"]) / "trace.jsonl").read_text()


def cycles(info: dict) -> int:
    path = Path(info["run_dir"]) / "trace.jsonl"
    return path.read_bytes().count(b"\n") if path.exists() else 0


def journal(info: dict) -> list[dict]:
    path = Path(info["run_dir"]) / "supervision.jsonl"
    return [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []


def wait_cycles(info: dict, n: int, timeout: float = 120) -> None:
    assert wait_for(lambda: cycles(info) >= n, timeout), f"stuck at {cycles(info)} < {n}"


def restarted(info: dict, name: str, timeout: float = 60) -> None:
    """Wait until the launcher has restarted `name` (its journal says so)."""
    assert wait_for(lambda: any(e["event"] == "exit" and e["name"] == name and e["restarted"]
                                for e in journal(info)), timeout), journal(info)


def pids_alive(pids) -> list[int]:
    out = []
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[-1].split()[0]
        except OSError:
            continue
        if state not in ("Z", "X"):
            out.append(pid)
    return out


def kill_all(pids) -> None:
    """Clean-up of a failed test: SIGKILL these pids if they are still there."""
    for pid in pids_alive(pids):
        os.kill(pid, signal.SIGKILL)


def summary(teleo: Teleo) -> dict:
    return json.loads((teleo.run_dir / "summary.json").read_text())


def finish(launcher: subprocess.Popen, timeout: float = 120) -> int:
    return launcher.wait(timeout)


def elapsed(since: float) -> float:
    return time.monotonic() - since
