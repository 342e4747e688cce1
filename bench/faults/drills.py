"""Fault drills against real launches: what happens, and how fast, when processes die, stall
or are attacked (docs/faults.md holds the table these figures feed).

    .venv/bin/python bench/faults/drills.py all                  # one trial of every drill
    .venv/bin/python bench/faults/drills.py kill --trials 3      # SIGKILL each process at random
    cycles .venv/bin/python bench/faults/drills.py stop --seconds 2     # SIGSTOP each stage, then
    SIGCONT .venv/bin/python bench/faults/drills.py router               # SIGKILL the router, then
    a stage .venv/bin/python bench/faults/drills.py router-record        # SIGKILL the router: the
    record .venv/bin/python bench/faults/drills.py launcher             # SIGKILL and SIGHUP the
    launcher .venv/bin/python bench/faults/drills.py ctrl-c               # Ctrl-C while a stage is
    stopped .venv/bin/python bench/faults/drills.py foreign              # a stranger on a secured
    run's bus .venv/bin/python bench/faults/drills.py full-disk            # a 2 MB run folder
    (root: tmpfs) .venv/bin/python bench/faults/drills.py teleo-stop --seconds 60  # `teleo stop` of
    a long run .venv/bin/python bench/faults/drills.py slow-record          # a recorder short of
    CPU (root) .venv/bin/python bench/faults/drills.py kill --secure        # the same on a secured
    bus

Each trial is a real `teleo launch` of the driving demo (or --scenario) in lockstep, in its
own TELEO_RUN_DIR, with real signals. A row per trial says at which cycle the fault came,
how long the launcher took to see it (the process's exit in supervision.jsonl), how long
until the run made progress again (two more cycles in the trace), the run's status and exit
code, and whether the trace is identical to an undisturbed run of the same scenario. The
drills of the record, the disk and `teleo stop` are in bench/faults/record_drills.py, the harness
(a launch in the background) in bench/faults/drill_launch.py.
"""

from __future__ import annotations

import os
import random
import signal
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import click
from drill_launch import DEMO, EXTRA, ROOT, Launch, Reference, pids_alive, reference, wait_for
from record_drills import (
    drill_full_disk,
    drill_router_record,
    drill_slow_record,
    drill_teleo_stop,
)

TARGETS = ("goals", "ME.perception", "ME.inference", "ME.executive", "world", "router")


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


def drill_signal(folder: Path, scenario: Path, ref: Reference, target: str, at: int,
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
            "identical": run.trace() == ref.trace, "restarts": s.get("restarts", {}),
            "stalls_s": [x["seconds"] for x in s.get("stalls", [])],
            "uncontrolled": s.get("uncontrolled", {})}


def drill_router(folder: Path, scenario: Path, ref: Reference, at: int) -> dict[str, Any]:
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
    try:   # a run that ended while a loaded machine kept the tool waiting has no stage left
        os.kill(run.pid("ME.inference"), signal.SIGKILL)
        back = progress_after(run, run.cycles())
    except (ProcessLookupError, KeyError):
        back = None
    rc = run.finish()
    s = run.summary()
    return {"drill": "SIGKILL router, then ME.inference", "cycle": base,
            "detected_ms": _ms(_first(run.journal(), "exit", "router", t0), t0),
            "progress_ms": _ms(reach, t0), "status": s.get("status"), "exit": rc,
            "identical": run.trace() == ref.trace, "restarts": s.get("restarts", {}),
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


def drill_launcher(folder: Path, scenario: Path, sig: signal.Signals) -> dict[str, Any]:
    """Kill the launcher of a run without a cycle limit; time until every process is gone."""
    run = Launch(folder, scenario, "--cycles", "0")
    pids = [int(p) for p in run.info()["pids"].values()]
    run.wait_cycle(50)
    t0 = time.time()
    os.kill(run.proc.pid, sig)
    gone = wait_for(lambda: not pids_alive(pids), 30.0)
    took = time.time() - t0
    left = pids_alive(pids)
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
    t0, wall = time.monotonic(), time.time()
    run.proc.send_signal(signal.SIGINT)
    rc = run.finish(60)
    took = time.monotonic() - t0
    s = run.summary()
    journal = {e["event"]: e for e in run.journal() if e["event"] in ("stopping", "stopped")}
    began, ended = journal.get("stopping", {}), journal.get("stopped", {})
    return {"drill": "Ctrl-C during a stall", "cycle": run.cycles(),
            "stop_ms": round(took * 1e3, 1), "status": s.get("status"), "exit": rc,
            "summary_cycles": s.get("cycles"), "left": len(pids_alive([stopped])),
            "to_stopping_ms": _ms(began.get("t"), wall), "launcher_s": ended.get("seconds"),
            **{f"{k}_s": ended.get(k) for k in ("processes", "record", "router")},
            "summary_ms": _ms(wall + took, ended["t"]) if "t" in ended else None}


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


class _Rows(list):
    """The drills' rows, each printed when it is added."""

    def append(self, row: dict[str, Any]) -> None:
        super().append(row)
        click.echo("  " + "  ".join(f"{k}={v}" for k, v in row.items()))

    def __iadd__(self, rows):  # rows += [...]
        for row in rows:
            self.append(row)
        return self


ONE_RUN = ("launcher", "foreign", "ctrl-c", "full-disk", "teleo-stop", "slow-record")
# (those need no undisturbed run to compare with)


@click.command()
@click.argument("which", type=click.Choice(["kill", "stop", "router", "router-record",
                                            "launcher", "ctrl-c", "foreign", "full-disk",
                                            "teleo-stop", "slow-record", "all"]))
@click.option("--trials", default=1, show_default=True, help="Trials per target.")
@click.option("--seconds", default=2.0, show_default=True,
              help="SIGSTOP length; for teleo-stop, how long the run runs first [s].")
@click.option("--seed", default=42, show_default=True, help="Seeds the fault cycles.")
@click.option("--scenario", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=DEMO, show_default=True)
@click.option("--secure", is_flag=True, help="Secured launches (clients of a TLS router).")
@click.option("--size", default="2m", show_default=True, help="full-disk: the tmpfs size.")
@click.option("--fill-at", type=int, default=300, show_default=True,
              help="full-disk: the cycle at which the second trial fills the disk at once.")
@click.option("--quota", default=5000, show_default=True,
              help="slow-record: the launcher's CPU [us per 100 ms].")
def main(which: str, trials: int, seconds: float, seed: int, scenario: Path,
         secure: bool, size: str, fill_at: int, quota: int) -> None:
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

        ref = Reference("", {}) if which in ONE_RUN else reference(scenario, folder())
        click.echo(f"drills on {scenario.name}{' secured' if secure else ''}, "
                   f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f} (each row as it "
                   f"comes):")
        rows = _Rows()   # printed as they come: a drill that crashes loses no earlier row
        for _ in range(trials):
            if which in ("kill", "all"):
                rows += (drill_signal(folder(), scenario, ref, t, rng.randrange(50, 500),
                                      signal.SIGKILL) for t in TARGETS)
            if which in ("stop", "all"):
                rows += (drill_signal(folder(), scenario, ref, t, rng.randrange(50, 500),
                                      signal.SIGSTOP, seconds) for t in TARGETS[:4])
            if which in ("router", "all"):
                rows.append(drill_router(folder(), scenario, ref, rng.randrange(50, 300)))
            if which in ("router-record", "all"):
                rows.append(drill_router_record(folder(), scenario, ref,
                                                rng.randrange(50, 500)))
            if which in ("launcher", "all"):
                rows += (drill_launcher(folder(), scenario, s)
                         for s in (signal.SIGKILL, signal.SIGHUP))
            if which in ("ctrl-c", "all"):
                rows.append(drill_ctrl_c(folder(), scenario, rng.randrange(50, 300)))
            if which in ("foreign", "all"):
                rows.append(drill_foreign(folder(), scenario))
            if which in ("full-disk", "all"):
                rows += (drill_full_disk(folder(), scenario, size, at) for at in (None, fill_at))
            if which in ("slow-record", "all"):
                rows.append(drill_slow_record(folder(), scenario, quota))
            if which in ("teleo-stop", "all"):
                rows.append(drill_teleo_stop(folder(), scenario, seconds if which != "all"
                                             else 20.0))
        click.echo(f"{len(rows)} drill(s), load {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
