"""Fault drills against real launches: what happens, and how fast, when processes die, stall
or are attacked (docs/faults.md holds the table these figures feed).

    .venv/bin/python bench/drills.py all                  # one trial of every drill
    .venv/bin/python bench/drills.py kill --trials 3      # SIGKILL each process at random cycles
    .venv/bin/python bench/drills.py stop --seconds 2     # SIGSTOP each stage, then SIGCONT
    .venv/bin/python bench/drills.py router               # SIGKILL the router, then a stage
    .venv/bin/python bench/drills.py launcher             # SIGKILL and SIGHUP the launcher
    .venv/bin/python bench/drills.py ctrl-c               # Ctrl-C while a stage is stopped
    .venv/bin/python bench/drills.py foreign              # a stranger on a secured run's bus
    .venv/bin/python bench/drills.py kill --secure        # the same on a secured bus

Each trial is a real `teleo launch` of the driving demo (or --scenario) in lockstep, in its
own TELEO_RUN_DIR, with real signals. A row per trial says at which cycle the fault came,
how long the launcher took to see it (the process's exit in supervision.jsonl), how long
until the run made progress again (two more cycles in the trace), the run's status and exit
code, and whether the trace is identical to an undisturbed run of the same scenario.
"""

from __future__ import annotations

import json
import os
import random
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import click

ROOT = Path(__file__).resolve().parents[1]
TELEO = str(Path(sys.executable).parent / "teleo")
DEMO = ROOT / "scenarios" / "driving_demo.toml"
TARGETS = ("goals", "ME.perception", "ME.inference", "ME.executive", "world", "router")


EXTRA: list[str] = []  # flags given to every launch (--secure)


class Launch:
    """One `teleo launch` in the background, with its own run folder."""

    def __init__(self, folder: Path, scenario: Path, *args: str) -> None:
        args = (*args, *(a for a in EXTRA if a not in args))
        self.folder = folder
        self.env = {**os.environ, "TELEO_RUN_DIR": str(folder)}
        self.out = (folder / "launch.out").open("w")
        self._info: dict[str, Any] | None = None
        self.proc = subprocess.Popen(
            [TELEO, "launch", str(scenario), "--summary", str(folder / "summary.json"), *args],
            cwd=ROOT, env=self.env, stdout=self.out, stderr=subprocess.STDOUT)

    def info(self, timeout: float = 120.0) -> dict[str, Any]:
        """The run file, once the launcher has registered the run (every process up); the
        pids are re-read while the run is registered (restarts change them)."""
        files = list((self.folder / "active").glob("*.json"))
        if files:
            self._info = json.loads(files[0].read_text())
        if self._info is not None:
            return self._info
        found = wait_for(lambda: list((self.folder / "active").glob("*.json"))
                         or self.proc.poll() is not None, timeout)
        files = list((self.folder / "active").glob("*.json"))
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


def reference(scenario: Path, folder: Path, *args: str) -> str:
    """The trace of an undisturbed launch of `scenario`."""
    run = Launch(folder, scenario, *args)
    run.info()
    rc = run.finish()
    if rc != 0:
        raise RuntimeError(f"reference launch failed ({rc}):\n{run.output()}")
    return run.trace()


def _first(events: list[dict[str, Any]], kind: str, name: str, after: float) -> float | None:
    times = [e["t"] for e in events if e["event"] == kind and e.get("name") == name
             and e["t"] >= after]
    return min(times) if times else None


def _ms(t: float | None, t0: float) -> float | None:
    return None if t is None else round((t - t0) * 1e3, 1)


def progress_after(run: Launch, base: int, timeout: float = 90.0) -> float | None:
    """When the trace reached two cycles past `base` [s since the epoch], or None."""
    if wait_for(lambda: run.cycles() >= base + 2 or run.proc.poll() is not None, timeout):
        return time.time() if run.cycles() >= base + 2 else None
    return None


def drill_signal(folder: Path, scenario: Path, ref: str, target: str, at: int,
                 sig: signal.Signals, seconds: float = 0.0) -> dict[str, Any]:
    """SIGKILL (or SIGSTOP for `seconds`) `target` when the trace reaches cycle `at`."""
    run = Launch(folder, scenario)
    run.info()
    run.wait_cycle(at)
    pid, base, t0 = run.pid(target), run.cycles(), time.time()
    os.kill(pid, sig)
    if sig == signal.SIGSTOP:
        time.sleep(seconds)
        os.kill(pid, signal.SIGCONT)
    back = progress_after(run, base)
    rc = run.finish()
    s = run.summary()
    return {"drill": f"{sig.name} {target}" + (f" {seconds:g} s" if seconds else ""),
            "cycle": base, "detected_ms": _ms(_first(run.journal(), "exit", target, t0), t0),
            "progress_ms": _ms(back, t0), "status": s.get("status"), "exit": rc,
            "identical": run.trace() == ref, "restarts": s.get("restarts", {}),
            "stalls_s": [x["seconds"] for x in s.get("stalls", [])],
            "uncontrolled": s.get("uncontrolled", {})}


def drill_router(folder: Path, scenario: Path, ref: str, at: int) -> dict[str, Any]:
    """SIGKILL the router; time until a tool reaches the run again; then SIGKILL a stage,
    which must rejoin through the restarted router."""
    run = Launch(folder, scenario)
    run.info()
    run.wait_cycle(at)
    base, t0 = run.cycles(), time.time()
    os.kill(run.pid("router"), signal.SIGKILL)
    reach = None
    if wait_for(lambda: _bus_ok(run.info()), 30.0, 0.05):
        reach = time.time()
    run.wait_cycle(base + 20)
    os.kill(run.pid("ME.inference"), signal.SIGKILL)
    back = progress_after(run, run.cycles())
    rc = run.finish()
    s = run.summary()
    return {"drill": "SIGKILL router, then ME.inference", "cycle": base,
            "detected_ms": _ms(_first(run.journal(), "exit", "router", t0), t0),
            "progress_ms": _ms(reach, t0), "status": s.get("status"), "exit": rc,
            "identical": run.trace() == ref, "restarts": s.get("restarts", {}),
            "stage_back": back is not None}


def _bus_ok(info: dict[str, Any]) -> bool:
    """Whether a new client (a tool) can reach the run and get the goal list answered."""
    sys.path.insert(0, str(ROOT))
    from bus import keys
    from bus.config import BusConfig
    from bus.errors import BusError
    from bus.messages import GoalRequest
    from bus.node import open_node

    cfg = BusConfig(mode="client", connect=(info["endpoint"],), listen=(),
                    connect_timeout_ms=200, credentials=info.get("credentials", ""))
    try:
        with open_node(cfg, info["run"], "drill") as node:
            node.query(keys.goals(info["run"], info["agents"][0]),
                       GoalRequest(node.envelope(), "list", info["agents"][0], "", 0, ""), 1.0)
        return True
    except BusError:
        return False


def _pids_alive(pids: list[int]) -> list[int]:
    out = []
    for pid in pids:
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            continue
        if stat.rsplit(")", 1)[-1].split()[0] not in ("Z", "X"):
            out.append(pid)
    return out


def drill_launcher(folder: Path, scenario: Path, sig: signal.Signals) -> dict[str, Any]:
    """Kill the launcher of a run without a cycle limit; time until every process is gone."""
    run = Launch(folder, scenario, "--cycles", "0")
    pids = [int(p) for p in run.info()["pids"].values()]
    run.wait_cycle(50)
    t0 = time.time()
    os.kill(run.proc.pid, sig)
    gone = wait_for(lambda: not _pids_alive(pids), 30.0)
    took = time.time() - t0
    left = _pids_alive(pids)
    for pid in left:  # clean up what did not follow (should be nothing)
        os.kill(pid, signal.SIGKILL)
    run.finish()
    return {"drill": f"{sig.name} launcher", "cycle": run.cycles(),
            "all_gone_ms": round(took * 1e3, 1) if gone else None, "left": len(left)}


def drill_ctrl_c(folder: Path, scenario: Path, at: int) -> dict[str, Any]:
    """SIGSTOP ME.inference, then Ctrl-C (SIGINT) the launcher 1 s later."""
    run = Launch(folder, scenario)
    run.info()
    run.wait_cycle(at)
    stopped = run.pid("ME.inference")
    os.kill(stopped, signal.SIGSTOP)
    time.sleep(1.0)
    t0 = time.monotonic()
    run.proc.send_signal(signal.SIGINT)
    rc = run.finish(60)
    took = time.monotonic() - t0
    s = run.summary()
    return {"drill": "Ctrl-C during a stall", "cycle": run.cycles(),
            "stop_ms": round(took * 1e3, 1), "status": s.get("status"), "exit": rc,
            "summary_cycles": s.get("cycles"), "left": len(_pids_alive([stopped]))}


def drill_foreign(folder: Path, scenario: Path) -> dict[str, Any]:
    """A secured run, and a stranger: no credentials, a wrong password, another process's
    credentials used to forge actions; the operator's credentials must still work."""
    sys.path.insert(0, str(ROOT))
    from bus.foreign import probe  # the checks, shared with tests/e2e/test_secure_live.py

    run = Launch(folder, scenario, "--cycles", "0", "--secure")
    info = run.info()
    run.wait_cycle(20)
    result = probe(info["endpoint"], info["run"], Path(info["run_dir"]) / "secrets")
    run.proc.send_signal(signal.SIGINT)
    run.finish(60)
    return {"drill": "stranger on a secured bus", **result}


def _print(rows: list[dict[str, Any]]) -> None:
    for row in rows:
        click.echo("  " + "  ".join(f"{k}={v}" for k, v in row.items()))


@click.command()
@click.argument("which", type=click.Choice(["kill", "stop", "router", "launcher", "ctrl-c",
                                            "foreign", "all"]))
@click.option("--trials", default=1, show_default=True, help="Trials per target.")
@click.option("--seconds", default=2.0, show_default=True, help="SIGSTOP length [s].")
@click.option("--seed", default=42, show_default=True, help="Seeds the fault cycles.")
@click.option("--scenario", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=DEMO, show_default=True)
@click.option("--secure", is_flag=True, help="Secured launches (clients of a TLS router).")
def main(which: str, trials: int, seconds: float, seed: int, scenario: Path,
         secure: bool) -> None:
    """Run fault drills against real launches and print what happened."""
    rng = random.Random(seed)
    EXTRA[:] = ["--secure"] if secure else []
    with tempfile.TemporaryDirectory(prefix="teleo-drills-") as tmp:
        box = Path(tmp)
        counter = iter(range(10**6))

        def folder() -> Path:
            path = box / f"d{next(counter)}"
            path.mkdir()
            return path

        ref = "" if which in ("launcher", "foreign", "ctrl-c") else reference(scenario, folder())
        rows: list[dict[str, Any]] = []
        for _ in range(trials):
            if which in ("kill", "all"):
                rows += [drill_signal(folder(), scenario, ref, t, rng.randrange(50, 500),
                                      signal.SIGKILL) for t in TARGETS]
            if which in ("stop", "all"):
                rows += [drill_signal(folder(), scenario, ref, t, rng.randrange(50, 500),
                                      signal.SIGSTOP, seconds) for t in TARGETS[:4]]
            if which in ("router", "all"):
                rows.append(drill_router(folder(), scenario, ref, rng.randrange(50, 300)))
            if which in ("launcher", "all"):
                rows += [drill_launcher(folder(), scenario, s)
                         for s in (signal.SIGKILL, signal.SIGHUP)]
            if which in ("ctrl-c", "all"):
                rows.append(drill_ctrl_c(folder(), scenario, rng.randrange(50, 300)))
            if which in ("foreign", "all"):
                rows.append(drill_foreign(folder(), scenario))
        click.echo(f"{len(rows)} drill(s) on {scenario.name}{' secured' if secure else ''}, "
                   f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}:")
        _print(rows)


if __name__ == "__main__":
    main()
