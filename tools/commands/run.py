"""`teleo ps` and `teleo stop [RUN]`: the runs of this host and their processes.

Both read the run registry (tools/runs/runfile.py). `ps` lists every registered run: its launcher
(running, or gone: a stale entry), router, whether it is secured, its folder, and each process
with its pid and whether it is still there. `stop` asks a run's launcher to stop it (SIGTERM:
the same orderly stop as Ctrl-C) and waits for it; if the launcher is already gone it stops
what is left of the run itself, SIGTERM then SIGKILL, touching only processes whose command
line names the run, and removes the stale entry; `stop --all` does so for every registered
run. A launcher stopped by Ctrl-C, SIGTERM or `teleo stop` removes its own entry; only one
killed outright (SIGKILL) leaves it, shown STALE: `ps --prune`, and the next launch, remove
such entries once nothing of their run is left.
"""

from __future__ import annotations

import json
import os
import signal
import time

import click

from tools.runs import runfile

STOP_TIMEOUT = 60.0  # [s] for a launcher to stop its run (2 s) and write its summary
KILL_AFTER = 2.0     # [s] between SIGTERM and SIGKILL for orphans


@click.command("ps")
@click.option("--json", "as_json", is_flag=True,
              help="JSON lines: one object per run (no line when none is registered).")
@click.option("--prune", is_flag=True,
              help="First remove the entries whose launcher is gone (saying which).")
def ps(as_json: bool, prune: bool) -> None:
    """List the runs on this host with their processes."""
    if prune:
        runfile.echo_pruned(*runfile.prune(), err=as_json)
    runs = runfile.all_runs()
    if as_json:
        for info, up in runs:
            doc = {"run": info.run, "launcher": info.pid, "running": up,
                   "endpoint": info.endpoint, "secured": info.secured, "joined": info.joined,
                   "run_dir": info.run_dir,
                   "processes": {n: {"pid": p, "alive": runfile.belongs(p, info.run)}
                                 for n, p in info.pids.items()}}
            click.echo(json.dumps(doc))
        return
    if not runs:
        click.echo(f"no runs registered in {runfile.registry()}")
        return
    click.echo(f"runs registered in {runfile.registry()}:")
    for info, up in runs:
        state = "running" if up else "STALE (launcher gone)"
        kind = ", joined" if info.joined else ""
        click.echo(f"{info.run}  launcher {info.pid} {state}  router {info.endpoint}"
                   f"{', secured' if info.secured else ''}{kind}  {info.run_dir}")
        for name, pid in info.pids.items():
            alive = "up" if runfile.belongs(pid, info.run) else "gone"
            click.echo(f"  {name:<24} pid {pid:<8} {alive}")


def _target(run: str | None) -> runfile.RunInfo:
    runs = [i for i, _ in runfile.all_runs()]
    if run is not None:
        match = [i for i in runs if i.run == run or i.key == run]
        if not match:
            raise click.ClickException(f"no run {run!r} in {runfile.registry()} (runs: "
                                       f"{', '.join(i.key for i in runs) or 'none'})")
        return match[0]
    if len(runs) == 1:
        return runs[0]
    if not runs:
        raise click.ClickException(f"no runs registered in {runfile.registry()}")
    raise click.ClickException(f"{len(runs)} runs registered ({', '.join(i.key for i in runs)})"
                               ": name the one to stop")


def _wait_gone(pids: list[int], run: str, timeout: float) -> list[int]:
    end = time.monotonic() + timeout
    left = [p for p in pids if runfile.belongs(p, run)]
    while left and time.monotonic() < end:
        time.sleep(0.05)
        left = [p for p in left if runfile.belongs(p, run)]
    return left


def _kill(pids: list[int], sig: signal.Signals) -> None:
    for pid in pids:
        try:
            os.kill(pid, sig)
        except ProcessLookupError:
            pass


@click.command("stop")
@click.argument("run", required=False)
@click.option("--all", "every", is_flag=True,
              help="Stop every registered run (and clean up after launchers that are gone).")
@click.option("--timeout", type=float, default=STOP_TIMEOUT, show_default=True,
              help="Seconds to wait for the launcher to stop the run.")
def stop(run: str | None, every: bool, timeout: float) -> None:
    """Stop RUN (default: the only registered run) and every process of it."""
    if every:
        if run is not None:
            raise click.UsageError("give RUN or --all, not both")
        runs = [i for i, _ in runfile.all_runs()]
        if not runs:
            click.echo(f"no runs registered in {runfile.registry()}")
        for info in runs:
            _stop(info, timeout)
        return
    _stop(_target(run), timeout)


def _stop(info: runfile.RunInfo, timeout: float) -> None:
    """Stop one registered run (see the module doc) and remove its entry."""
    launcher = runfile.alive(info.pid) and "launch" in runfile.cmdline(info.pid)
    if launcher:
        os.kill(info.pid, signal.SIGTERM)
        if _wait_gone([info.pid], "launch", timeout):
            click.echo(f"launcher {info.pid} did not stop within {timeout:g} s: killed",
                       err=True)
            _kill([info.pid], signal.SIGKILL)
    left = [p for p in info.pids.values() if runfile.belongs(p, info.run)]
    if left:  # the launcher was gone, or its processes outlived it
        _kill(left, signal.SIGCONT)
        _kill(left, signal.SIGTERM)
        stubborn = _wait_gone(left, info.run, KILL_AFTER)
        _kill(stubborn, signal.SIGKILL)
        click.echo(f"stopped {len(left)} process(es) of {info.run} left without a launcher"
                   + (f" ({len(stubborn)} killed)" if stubborn else ""))
    runfile.remove(info)
    if launcher or left:
        click.echo(f"run {info.run} stopped")
    else:  # nothing of it was running: say what was done
        click.echo(f"run {info.run} was not running (its launcher {info.pid} is gone); its "
                   f"stale entry is removed")


commands = [ps, stop]
