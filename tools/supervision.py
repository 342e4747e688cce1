"""The supervision loop of one `teleo launch` (tools/launch.py): start the router and the
local processes of a plan, wait until they are up, register the run, restart what dies, end
the run when it is over, stop everything quickly.

What it does on each fault (docs/faults.md has the table with measured times):
- a stage or the goal-entry process exits: restarted at once (its respawn policy); the clock
  re-sends the current state and it rejoins at the current cycle;
- the world exits: restarted with --resume (it replays to the cycle reached); a world that
  cannot resume, or whose stages never all came up, ends the run with that reason;
- the router exits: restarted on the same endpoint; every process reconnects to it;
- a process is left down (restarts used up): the run ends at once, as failed;
- Ctrl-C, SIGTERM or SIGHUP: the run is stopped within about two seconds, in any state.

It also records, in the run folder's supervision.jsonl, when each process was seen gone and
when each came back (its liveliness token appeared again): bench/drills.py reads it for
detection and recovery times.
"""

from __future__ import annotations

import json
import logging
import os
import time
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import click

from bus.errors import BusError
from tools import runfile
from tools.progress import WorldProgress
from tools.run_plan import Plan, bus_config, process_specs, start_timeout
from tools.supervisor import Exit, ProcSpec, Supervisor

log = logging.getLogger(__name__)
POLL_S = 0.05           # [s] between looks at the children when nothing else wakes us
JOIN_GRACE_S = 5.0      # [s] a joined launch waits after the main launcher's token is gone
ROUTER_RESTARTS = 10
EXIT_CANNOT_RESUME, EXIT_NOT_READY = 3, 4  # world/process.py


@dataclass
class Outcome:
    """How the launch ended: restarts per process, processes left down, the launcher's reason
    for ending the run early, and whether a user asked for the stop."""

    restarts: dict[str, int] = field(default_factory=dict)
    left_down: tuple[str, ...] = ()
    ended: str = ""
    requested_stop: bool = False


class _Journal:
    """supervision.jsonl: what the launcher saw, with wall-clock times [s]."""

    def __init__(self, path: Path) -> None:
        path.parent.mkdir(parents=True, exist_ok=True)
        self.path = path

    def write(self, event: str, **fields: Any) -> None:
        line = json.dumps({"t": round(time.time(), 4), "event": event, **fields})
        with self.path.open("a") as f:
            f.write(line + "\n")


def supervise(plan: Plan) -> Outcome:
    """Run the plan to its end (see the module doc); never raises on a process's fault."""
    plan.run_dir.mkdir(parents=True, exist_ok=True)
    sup = Supervisor(plan.run_dir / "logs")
    journal = _Journal(plan.run_dir / "supervision.jsonl")
    outcome = Outcome()
    info: runfile.RunInfo | None = None
    recorder = None
    try:
        if not plan.joined:
            plan = _start_router(plan, sup)
        if plan.record and plan.runs_world:
            from tools.recorder import start_run_recorder

            # subscribed before any process starts, so the record holds cycle 0
            recorder = start_run_recorder(bus_config(plan, "operator"), plan.run,
                                          plan.run_dir, plan.scenario)
        specs = process_specs(plan)
        for spec in specs:
            sup.start(spec)
        where = "on the joined router" if plan.joined else "and a router at"  # not counted
        mode = ", secured" if plan.secrets else ", clients of the router" if plan.client else ""
        click.echo(f"run {plan.run}: {len(specs)} processes {where} {plan.endpoint}{mode}, "
                   f"logs in {plan.run_dir / 'logs'}")
        info = _loop(plan, sup, journal, outcome)
    except KeyboardInterrupt:
        click.echo("interrupted: stopping the run")
        outcome.requested_stop = True
    except (click.ClickException, BusError) as exc:  # BusError: the router cannot be reached
        outcome.ended = exc.message if isinstance(exc, click.ClickException) else str(exc)
        click.echo(f"Error: {outcome.ended}", err=True)
    finally:
        t0 = time.monotonic()
        sup.stop_all(["world"], keep=["router"])
        journal.write("stopped", seconds=round(time.monotonic() - t0, 3))
        if recorder is not None:  # drained while the router still holds what it is owed
            recorder.stop()
        sup.stop_all([], last=["router"])
        if info is not None:
            runfile.remove(info)
    outcome.restarts = sup.restarts()
    return outcome


def _start_router(plan: Plan, sup: Supervisor) -> Plan:
    from bus.lifeline import ENV_PARENT
    from bus.router import router_argv, spawn_router

    security = str(plan.secrets.router) if plan.secrets else ""
    env = {ENV_PARENT: str(os.getpid())}
    log_file = plan.run_dir / "logs" / "router.log"
    router = spawn_router(plan.listen, security=security, env=env, log_file=str(log_file),
                          run=plan.run)
    # restarts listen on the very endpoint the processes know (same port)
    sup.adopt(ProcSpec("router", router_argv(router.endpoint, security, plan.run),
                       ROUTER_RESTARTS, env=env), router.proc)
    return replace(plan, endpoint=router.endpoint)


def _loop(plan: Plan, sup: Supervisor, journal: _Journal, outcome: Outcome) -> runfile.RunInfo:
    from bus.node import open_node

    cfg = bus_config(plan, "launch")
    with open_node(cfg, plan.run, "launch" if not plan.joined else f"join-{os.getpid()}") as node:
        _wait_ready(sup, node, plan)
        _show_status(sup, node.alive())
        info = runfile.RunInfo(plan.run, plan.endpoint, os.getpid(), tuple(plan.scenario.agent_ids),
                               str(plan.run_dir), str(plan.scenario.path), sup.pids(),
                               str(plan.secrets.credentials("operator")) if plan.secrets else "",
                               plan.joined, time.time())
        runfile.write(info)
        if not plan.joined:
            node.announce()  # joined launches end when this token goes
        journal.write("ready", processes=sup.names())
        with WorldProgress(node, plan.run, plan.cycles if plan.runs_world else 0) as bar:
            _watch(plan, sup, node, journal, outcome, info, bar)
    return info


def _watch(plan: Plan, sup: Supervisor, node, journal: _Journal, outcome: Outcome,
           info: runfile.RunInfo, bar: WorldProgress) -> None:
    seen = dict(node.presence.incarnations())
    main_gone_since: float | None = None
    while True:
        bar.poll()
        exits = sup.poll(restartable=_restartable)
        for ex in exits:
            journal.write("exit", name=ex.name, rc=ex.returncode, restarted=ex.restarted)
            _tell(plan, ex)
        if exits:
            runfile.write(replace(info, pids=sup.pids(),
                                  restarts={n: k for n, k in sup.restarts().items() if k}))
        ended = _ended(plan, sup, exits)
        if ended is not None:
            outcome.ended = ended
            # a world that finished (ended == "") is not "left down"; one that failed is
            outcome.left_down = tuple(n for n in sup.left_down() if n != "world" or ended)
            return
        now = dict(node.presence.incarnations())
        for name, n in now.items():
            if n != seen.get(name):
                journal.write("up", name=name, incarnation=n)
        seen = now
        if plan.joined:
            main_gone_since = _main_launcher(node, main_gone_since)
            if main_gone_since is not None and time.monotonic() - main_gone_since > JOIN_GRACE_S:
                return
        node.presence.wait_change(POLL_S)


def _restartable(name: str, rc: int) -> bool:
    """The world is not restarted when it finished (0), cannot resume or never got ready."""
    return not (name == "world" and rc in (0, EXIT_CANNOT_RESUME, EXIT_NOT_READY))


def _ended(plan: Plan, sup: Supervisor, exits: list[Exit]) -> str | None:
    """None while the run goes on; else "" (the world finished) or the reason it ends."""
    for ex in exits:
        if ex.name == "world" and not ex.restarted:
            if ex.returncode == 0:
                return ""
            tail = _log_tail(plan.run_dir / "logs" / "world.log", 1)
            return f"the world exited with code {ex.returncode} and was not restarted: {tail}"
    down = [n for n in sup.left_down() if n != "world"]
    if down:
        return f"{', '.join(down)} left down after its restarts: the run cannot go on"
    return None


def _tell(plan: Plan, ex: Exit) -> None:
    if ex.restarted:
        how = " on the same endpoint" if ex.name == "router" else (
            ", resuming" if ex.name == "world" else "")
        click.echo(f"{ex.name} exited with code {ex.returncode}: restarted ({ex.restarts}){how}",
                   err=True)
    elif not (ex.name == "world" and ex.returncode == 0):
        click.echo(f"{ex.name} exited with code {ex.returncode}: left down", err=True)


def _main_launcher(node, gone_since: float | None) -> float | None:
    """When the main launcher's token was first missed after it had been seen (None while
    it is there, or before it ever was: a launch may join before the main one is ready)."""
    if "launch" in node.presence.snapshot():
        return None
    if gone_since is None and not node.presence.incarnations().get("launch"):
        return None
    return gone_since if gone_since is not None else time.monotonic()


def _wait_ready(sup: Supervisor, node, plan: Plan) -> None:
    """Wait until every local process has announced itself; fail fast, with the end of its
    log, when one exits during start-up."""
    expected = set(plan.local)
    timeout = start_timeout(len(expected))
    end = time.monotonic() + timeout
    log_dir = plan.run_dir / "logs"
    while not expected <= node.alive():
        for ex in sup.poll():
            if ex.name == "router":
                continue
            tail = _log_tail(log_dir / f"{ex.name}.log")
            raise click.ClickException(f"{ex.name} exited with code {ex.returncode} while "
                                       f"starting; end of its log:\n{tail}")
        if time.monotonic() > end:
            missing = sorted(expected - node.alive())
            raise click.ClickException(f"not every process announced itself within "
                                       f"{timeout:g} s: missing {missing}; see {log_dir}")
        node.presence.wait_change(0.1)


def _log_tail(path: Path, lines: int = 12) -> str:
    try:
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])
    except FileNotFoundError:
        return "(no log)"


def _show_status(sup: Supervisor, alive: set[str]) -> None:
    for name in sup.names():
        state = "up" if name in alive or name == "router" else (
            "running" if sup.running(name) else "exited")
        click.echo(f"  {name:<24} pid {sup.pid(name):<8} {state}")
