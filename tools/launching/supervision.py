"""The supervision loop of one `teleo launch` (tools/commands/launch.py): start the router and the
local processes of a plan, wait until they are up, register the run, restart what dies, end
the run when it is over, stop everything quickly.

What it does on each fault (docs/faults.md has the table with measured times):
- a stage or the goal-entry process exits: restarted at once (its respawn policy); the clock
  re-sends the current state and it rejoins at the current cycle;
- the world exits: restarted with --resume (it replays to the cycle reached); a world that
  cannot resume, or whose stages never all came up, ends the run with that reason;
- the router exits: restarted on the same endpoint; every process reconnects to it;
- a process is left down (restarts used up): the run ends at once, as failed;
- the world cannot write its run folder (a full disk): the run ends as failed, with the
  reason; before that, the launcher stops the run itself once the folder's file system is
  nearly full, while every file can still be closed whole (tools/launching/diskspace.py);
- Ctrl-C, SIGTERM or SIGHUP, at any moment from the command's start: the run is stopped in
  order (tools/launching/run_stop.py, tools/launching/stop_signals.py), its registry entry removed.

Registering the run also removes the stale entries other launches left (their launcher
killed outright, and nothing of their run left). It records, in the run folder's
supervision.jsonl, when each process was seen gone and when each came back (its liveliness
token appeared again), and how long each part of the stop took: bench/faults/drills.py reads it.
"""

from __future__ import annotations

import logging
import os
import time
from dataclasses import replace
from pathlib import Path

import click

from bus.errors import BusError
from tools.launching import stop_signals
from tools.launching.diskspace import free_text, shortage
from tools.launching.progress import WorldProgress
from tools.launching.run_plan import Plan, bus_config, process_specs, start_timeout
from tools.launching.run_stop import Held, Journal, Outcome, stop_run, trace_cycles
from tools.launching.supervisor import Exit, ProcSpec, Supervisor
from tools.paths import describe_os_error
from tools.runs import runfile

log = logging.getLogger(__name__)
POLL_S = 0.05           # [s] between looks at the children when nothing else wakes us
JOIN_GRACE_S = 5.0      # [s] a joined launch waits after the main launcher's token is gone
ROUTER_RESTARTS = 10
EXIT_CANNOT_RESUME, EXIT_NOT_READY, EXIT_CANNOT_WRITE = 3, 4, 5  # world/process.py
ROOM_EVERY_S = 0.2      # [s] between looks at the run folder's free space


def supervise(plan: Plan) -> Outcome:
    """Run the plan to its end (see the module doc); never raises on a process's fault."""
    try:
        plan.run_dir.mkdir(parents=True, exist_ok=True)
        sup = Supervisor(plan.run_dir / "logs")
    except OSError as exc:
        raise click.ClickException(f"cannot make the run folder: "
                                   f"{describe_os_error(exc)}") from exc
    short = shortage(plan.run_dir)
    if short:  # nothing started: a run there would be stopped as soon as it began
        raise click.ClickException(f"not started: the run folder {plan.run_dir} is on a file "
                                   f"system that {short}")
    journal = Journal(plan.run_dir / "supervision.jsonl")
    outcome, held = Outcome(), Held()
    try:
        _start(plan, sup, journal, outcome, held)
    except KeyboardInterrupt:
        stop_signals.stopping(held.cut_short)  # first: a second signal must not break the stop
        click.echo("interrupted: stopping the run")
        outcome.requested_stop = True
    except (click.ClickException, BusError) as exc:  # BusError: the router cannot be reached
        outcome.ended = exc.message if isinstance(exc, click.ClickException) else str(exc)
        click.echo(f"Error: {outcome.ended}", err=True)
    except OSError as exc:  # a file of the launcher's own could not be written
        outcome.ended = f"the launcher could not go on: {describe_os_error(exc)}"
        click.echo(f"Error: {outcome.ended}", err=True)
    finally:
        stop_signals.stopping(held.cut_short)  # nothing from here on breaks off the stop
        stop_run(plan, sup, journal, outcome, held)
    outcome.restarts = sup.restarts()
    return outcome


def _start(plan: Plan, sup: Supervisor, journal: Journal, outcome: Outcome,
           held: Held) -> None:
    """Start the router, the recorder and the processes, then watch the run to its end."""
    if not plan.joined:
        plan = _start_router(plan, sup)
    if plan.record and plan.runs_world:
        _start_recorder(plan, held)  # subscribed before any process starts: cycle 0 is in
        if held.recorder is None:    # the world does not wait for a recorder that is not
            plan = replace(plan, record=False)
    elif plan.runs_world:            # no record: the goal histories all the same
        _start_goal_watch(plan, held)
    specs = process_specs(plan)
    for spec in specs:
        sup.start(spec)
    where = "on the joined router" if plan.joined else "and a router at"  # not counted
    mode = ", secured" if plan.secrets else ", clients of the router" if plan.client else ""
    click.echo(f"run {plan.run}: {len(specs)} processes {where} {plan.endpoint}{mode}, "
               f"logs in {plan.run_dir / 'logs'}")
    _loop(plan, sup, journal, outcome, held)


def _start_recorder(plan: Plan, held: Held) -> None:
    """The run's recorder (tools/records/run_recorders.py); when it cannot start the run goes on
    unrecorded, said on the log."""
    from tools.records.run_recorders import run_recorder

    try:
        held.recorder = run_recorder(bus_config(plan, "operator"), plan.run, plan.run_dir,
                                     plan.scenario)
        held.recorder.start()
    except (BusError, OSError) as exc:
        log.error("run %s is not recorded: %s", plan.run, exc)
        if held.recorder is not None:
            held.recorder.writer.close()
        held.recorder = None


def _start_goal_watch(plan: Plan, held: Held) -> None:
    """--no-record: the goal histories for the summary (tools/records/goal_watch.py); when
    it cannot start the summary lists the goals without them, said on the log."""
    from tools.records.goal_watch import GoalWatch

    try:
        held.goal_watch = GoalWatch(bus_config(plan, "operator"), plan.run,
                                    plan.run_dir).start()
    except BusError as exc:
        log.error("run %s: no goal histories: %s", plan.run, exc)


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


def _loop(plan: Plan, sup: Supervisor, journal: Journal, outcome: Outcome,
          held: Held) -> None:
    from bus.node import open_node

    cfg = bus_config(plan, "launch")
    name = "launch" if not plan.joined else f"join-{os.getpid()}"
    node = held.session.enter_context(open_node(cfg, plan.run, name))  # closed by stop_run
    _wait_ready(sup, node, plan)
    _show_status(sup, node.alive())
    held.info = runfile.RunInfo(plan.run, plan.endpoint, os.getpid(),
                                tuple(plan.scenario.agent_ids), str(plan.run_dir),
                                str(plan.scenario.path), sup.pids(),
                                str(plan.secrets.credentials("operator")) if plan.secrets
                                else "", plan.joined, time.time())
    _register(held.info)
    if not plan.joined:
        node.announce()  # joined launches end when this token goes
    journal.write("ready", processes=sup.names())
    with WorldProgress(node, plan.run, plan.cycles if plan.runs_world else 0) as bar:
        _watch(plan, sup, node, journal, outcome, held.info, bar)


def _register(info: runfile.RunInfo, update: bool = False) -> None:
    """Write the run's registry entry (first removing stale ones, whose launcher is gone
    and nothing of whose run is left: tools/commands/run.py); one that cannot be written is
    said, and the run goes on (the tools will not find it)."""
    if not update:
        runfile.echo_pruned(*runfile.prune())
    try:
        runfile.write(info)
    except OSError as exc:
        log.warning("run %s: registry entry %s not written (%s): the tools will not find it",
                    info.run, runfile.path_of(info), exc.strerror)


def _watch(plan: Plan, sup: Supervisor, node, journal: Journal, outcome: Outcome,
           info: runfile.RunInfo, bar: WorldProgress) -> None:
    seen = dict(node.presence.incarnations())
    main_gone_since: float | None = None
    room_at = 0.0
    while True:
        bar.poll()
        exits = sup.poll(restartable=_restartable)
        for ex in exits:
            journal.write("exit", name=ex.name, rc=ex.returncode, restarted=ex.restarted)
            _tell(plan, ex)
        if exits:
            _register(replace(info, pids=sup.pids(),
                              restarts={n: k for n, k in sup.restarts().items() if k}),
                      update=True)
        ended = _ended(plan, sup, exits)
        if ended is None and time.monotonic() >= room_at:
            room_at = time.monotonic() + ROOM_EVERY_S
            ended = _short_of_room(plan)
        if ended is not None:
            outcome.ended = ended
            # a world that finished (ended == "") is not "left down", nor one that stopped
            # because it cannot write (`ended` says so); one that failed is
            quiet = ended == "" or any(ex.name == "world" and ex.returncode == EXIT_CANNOT_WRITE
                                       for ex in exits)
            outcome.left_down = tuple(n for n in sup.left_down() if n != "world" or not quiet)
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


def _short_of_room(plan: Plan) -> str | None:
    """The reason to stop the run when its folder's file system is nearly full (stopped
    while every file can still be closed whole: tools/launching/diskspace.py), else None."""
    short = shortage(plan.run_dir)
    if not short:
        return None
    return f"the run was stopped: its folder {plan.run_dir} is on a file system that {short}"


def _restartable(name: str, rc: int) -> bool:
    """The world is not restarted when it finished (0), cannot resume, never got ready, or
    cannot write its run folder (a restart would fail the same way)."""
    return not (name == "world" and rc in (0, EXIT_CANNOT_RESUME, EXIT_NOT_READY,
                                           EXIT_CANNOT_WRITE))


def _ended(plan: Plan, sup: Supervisor, exits: list[Exit]) -> str | None:
    """None while the run goes on; else "" (the world finished) or the reason it ends."""
    for ex in exits:
        if ex.name == "world" and not ex.restarted:
            if ex.returncode == 0:
                return ""
            if ex.returncode == EXIT_CANNOT_WRITE:
                return (f"the world stopped at cycle {trace_cycles(plan.run_dir)}: it could "
                        f"not write its files in {plan.run_dir} "
                        f"({free_text(plan.run_dir) or 'see its log'})")
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
    elif ex.name == "world" and ex.returncode == EXIT_CANNOT_WRITE:
        click.echo(f"world stopped (code {ex.returncode}): it cannot write its run folder",
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
