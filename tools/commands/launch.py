"""`teleo launch SCENARIO`: start every process of a scenario, supervise, stop, summarise.

Order of a launch: a router (bus.router.spawn_router), then the goal-entry process, each
agent's perception, inference and executive, and the world (the clock, which waits for all
the others). The launcher waits until every process has announced itself (liveliness), shows
their status, registers the run (tools/runs/runfile.py), restarts any process that dies (the
router on the same endpoint, the world with --resume: docs/faults.md) per its respawn policy,
and ends the run when the world finishes, when a process is left down (its restarts used up),
or on Ctrl-C, SIGTERM or SIGHUP; it then stops every process within about two seconds,
unregisters the run and prints the summary (tools/records/summary.py), whose status is its exit
code. If the launcher itself is killed, every process of the run follows it (bus/lifeline.py).

`--secure` (or `[run] secure = true`) runs the bus with TLS, a user and password per process
and an access-control list (bus/security.py); `--only` and `--join` spread one run over
several hosts (tools/launching/run_plan.py, docs/faults.md "Across hosts").
"""

from __future__ import annotations

import json
import logging
import os
import re
import secrets
import shutil
import sys
import time
from contextlib import nullcontext, redirect_stdout
from dataclasses import replace
from pathlib import Path

import click

from tools.commands.examples import ScenarioArg
from tools.commands.plot import plot_check
from tools.commands.scenario_check import check_learned, load_checked, override_option
from tools.launching import stop_signals
from tools.launching.placement import PerProcess, layout_line, placement_of
from tools.launching.run_plan import (
    Plan,
    PlanError,
    check_secrets,
    claim_run_dir,
    select,
    start_timeout,
    uses_clients,
    with_bus_mode,
)
from tools.launching.run_secrets import RunSecrets, host_of, make_secrets
from tools.launching.supervision import Outcome, supervise
from tools.paths import OutputPath, describe_os_error, picture_check
from tools.records import run_status, summary
from tools.runs import runfile
from world.errors import WorldError
from world.run_scenario import Scenario, ScenarioError

log = logging.getLogger(__name__)
REMOTE_READY_TIMEOUT = 600.0  # [s] the world waits for stages started on other hosts


@click.command()
@click.argument("scenario_file", metavar="SCENARIO", type=ScenarioArg())
@click.option("--cycles", type=click.IntRange(min=0), help="Cycles to run (0: forever).")
@click.option("--seed", type=int, help="World seed (overrides [run].seed).")
@click.option("--mode", type=click.Choice(["lockstep", "realtime"]), help="Clock mode.")
@click.option("--summary", "summary_file", type=OutputPath(),
              help="Write the summary JSON here.")
@click.option("--render", "render_file", type=OutputPath(picture_check),
              help="Draw the run: a .png of the last state or a .gif of the run.")
@click.option("--secure", is_flag=True, help="TLS, a user per process and access control "
              "(also [run] secure = true).")
@click.option("--listen", default=None, metavar="ENDPOINT",
              help="Where the router listens [default tcp/127.0.0.1:0, or tls/... secured], "
                   "e.g. tls/10.0.0.1:7447 for agents on other hosts.")
@click.option("--host", "hosts", multiple=True, metavar="NAME",
              help="Another name or address of this host for the router's certificate.")
@click.option("--only", default=None, metavar="NAMES",
              help="Start only these: world, goals, an agent id or a process name, "
                   "comma-separated (the others run on other hosts).")
@click.option("--join", "join", default=None, metavar="ENDPOINT",
              help="Join the run whose router is at ENDPOINT (needs --run; starts no router).")
@click.option("--run", "run_id", default=None,
              help="Run id (required with --join); refused when an earlier run has its folder.")
@click.option("--secrets", "secrets_dir", default=None, type=click.Path(file_okay=False),
              help="A secured run's secrets folder (copied from the first host, with --join).")
@click.option("--learned", type=click.Path(exists=True, dir_okay=False),
              help="Start every agent from the skills learned in an earlier run (its "
                   "learned-AGENT.tlp); the run's own file holds them plus the new ones.")
@click.option("--plot", "plot_file", type=OutputPath(plot_check),
              help="Plot the run record (PNG): speed, goal timeline, stage times.")
@click.option("--no-record", is_flag=True, help="Do not write the run record (record.mcap).")
@click.option("--agents-per-process", type=PerProcess(), default="0", metavar="K|auto",
              help="Run K agents' perception, inference and executive in one process "
                   "(0: a process per stage; auto: the agents spread over this machine's "
                   "CPUs, the fastest from 2 agents on). Not with --secure, --only, --join "
                   "or --listen beyond this host.")
@override_option
@click.option("--json", "as_json", is_flag=True,
              help="Print the summary as one JSON object on stdout (everything else on stderr).")
def launch(scenario_file: str, cycles: int | None, seed: int | None, mode: str | None,
           summary_file: str | None, render_file: str | None, secure: bool,
           listen: str | None, hosts: tuple[str, ...], only: str | None, join: str | None,
           run_id: str | None, secrets_dir: str | None, learned: str | None,
           plot_file: str | None, no_record: bool, agents_per_process: int | str,
           overrides: tuple[str, ...], as_json: bool) -> None:
    """Start every process of SCENARIO, supervise them, and summarise the run.

    The processes are zenoh peers of each other, or clients of the router when there are
    more than 30 (docs/bus.md). `--set KEY=VALUE` changes a field of the scenario for this
    run (`--cycles`, `--seed` and `--mode` win over it). Environment: TELEO_RUN_DIR, where
    runs are kept (else ./out); TELEO_PROFILE=DIR, every process writes a cProfile of its
    run to DIR.
    """
    if plot_file and no_record:
        raise click.UsageError("--plot draws the run record: leave out --no-record")
    plan = None
    try:
        # SIGINT, SIGTERM, SIGHUP: stop in order (tools/launching/stop_signals.py)
        stop_signals.running()
        scenario, _ = load_checked(scenario_file, overrides)
        if learned:
            check_learned(scenario, learned)
        plan = _plan(scenario, cycles, seed, mode, secure or scenario.run.secure, listen,
                     hosts, only, join, run_id, secrets_dir)
        per_process, cpus = placement_of(agents_per_process, len(scenario.agents))
        plan = replace(plan, learned=learned, record=not no_record,
                       agents_per_process=per_process)
        if per_process and (plan.client or only):
            raise PlanError("--agents-per-process: only for a whole open run on one host "
                            "(not with --secure, --only, --join or --listen beyond it)")
        plan = with_bus_mode(plan)
        if plan.joined:
            _reach_router(plan)
    except (ScenarioError, PlanError, WorldError) as exc:
        _unclaim(plan)
        raise click.ClickException(str(exc)) from exc
    except KeyboardInterrupt:
        _unclaim(plan)
        stop_signals.stopping()
        click.echo("interrupted before the run started: no process was started", err=True)
        raise SystemExit(run_status.EXIT_CODES["interrupted"]) from None
    base = {"run": plan.run, "scenario": str(scenario.path), "mode": plan.mode,
            "seed": plan.seed, "cycles_requested": plan.cycles,
            "secured": plan.secrets is not None, "overrides": list(scenario.overrides),
            "status_policy": scenario.run.status}
    with redirect_stdout(sys.stderr) if as_json else nullcontext():
        if per_process:
            click.echo(layout_line(len(scenario.agents), per_process, cpus))
        outcome = supervise(plan)
        if not plan.runs_world:
            _echo_joined(plan, outcome)
            raise SystemExit(1 if outcome.left_down or outcome.ended else 0)
        result = summary.build(plan.run_dir, base, outcome.restarts, scenario.domain,
                               outcome.left_down, outcome.ended, outcome.requested_stop,
                               scenario.events, outcome.recorder)
        unwritten = _finish(result, scenario, plan.run_dir, summary_file, render_file,
                            plot_file, as_json)
    if as_json:
        click.echo(json.dumps(result, indent=1))
    code = run_status.exit_code(result)
    raise SystemExit(code if code or not unwritten else 1)


def _finish(result: dict, scenario: Scenario, run_dir: Path, summary_file: str | None,
            render_file: str | None, plot_file: str | None, as_json: bool) -> bool:
    """The summary for a person (unless --json), its file, the picture, the plot; returns
    whether the summary file could not be written (said on stderr: a full disk)."""
    if not as_json:
        summary.echo(result)
    if summary_file:
        try:
            Path(summary_file).parent.mkdir(parents=True, exist_ok=True)
            Path(summary_file).write_text(json.dumps(result, indent=1))
        except OSError as exc:
            click.echo(f"Error: the summary was not written: {describe_os_error(exc)}",
                       err=True)
            return True
        click.echo(f"summary written to {summary_file}")
    if render_file:
        frames = summary.render(run_dir, Path(render_file), scenario.agent_ids[0])
        click.echo(f"picture written to {render_file} ({frames} frame(s))" if frames
                   else "no snapshots saved: nothing rendered")
    if plot_file:
        from tools.commands.plot import plot_command_output

        click.echo(plot_command_output(run_dir, Path(plot_file)))
    return False


def _plan(scenario, cycles, seed, mode, secure, listen, hosts, only, join, run_id,
          secrets_dir) -> Plan:
    if join and not run_id:
        raise PlanError("--join needs --run RUN, the id of the run to join")
    if join and secure and not secrets_dir:
        raise PlanError("--join of a secured run needs --secrets FOLDER (copied from the "
                        "host that started the run)")
    listen = listen or ("tls/127.0.0.1:0" if secure else "tcp/127.0.0.1:0")
    if secure and not (join or listen).startswith("tls/"):
        raise PlanError(f"a secured run listens and connects on tls/ endpoints, got "
                        f"{join or listen!r}")
    run = run_id or f"{scenario.run.name}-{secrets.token_hex(3)}"
    _check_run_id(run, "--run" if run_id else "[run].name")
    local = select(scenario, only)
    run_dir = runfile.base_dir() / "runs" / run
    if join:
        run_dir = run_dir.with_name(f"{run}.join-{os.getpid()}")
    else:
        run, run_dir = claim_run_dir(run, run_dir, bool(run_id), scenario.run.name, secure)
    try:
        return _planned(scenario, cycles, seed, mode, secure, listen, hosts, join, secrets_dir,
                        run, run_dir, local)
    except BaseException:
        if not join:
            shutil.rmtree(run_dir, ignore_errors=True)   # new and ours (claim_run_dir): nothing ran
        raise


def _planned(scenario, cycles, seed, mode, secure, listen, hosts, join, secrets_dir, run,
             run_dir, local) -> Plan:
    keep = None
    if secure:
        keep = RunSecrets(Path(secrets_dir).resolve()) if secrets_dir else None
        if keep is None:
            run_dir.mkdir(parents=True, exist_ok=True, mode=0o700)
            keep = make_secrets(run_dir / "secrets", run, scenario.agent_ids,
                                [h for h in (host_of(listen), *hosts) if h])
    plan = Plan(scenario, run, run_dir, scenario.run.cycles if cycles is None else cycles,
                scenario.run.seed if seed is None else seed,
                mode or scenario.run.mode.value, local, endpoint=join or "", listen=listen,
                secrets=keep,
                client=uses_clients(secure, bool(join), join or listen), joined=bool(join),
                ready_timeout=REMOTE_READY_TIMEOUT if len(local) < len(select(scenario, None))
                else start_timeout(len(local)))
    check_secrets(plan)
    return plan


def _unclaim(plan: Plan | None) -> None:
    """Remove the folder a launch claimed (run_plan.claim_run_dir) when it stops before starting."""
    if plan is not None and not plan.joined:
        shutil.rmtree(plan.run_dir, ignore_errors=True)


def _reach_router(plan: Plan) -> None:
    """Refuse a --join whose router does not answer (within the bus's connect timeout, 5 s),
    before anything is started or written: no run folder, no process left behind."""
    from bus.errors import BusError
    from bus.node import open_node
    from tools.launching.run_plan import bus_config

    try:
        with open_node(bus_config(plan, "launch"), plan.run, f"join-{os.getpid()}"):
            pass
    except BusError as exc:
        reason = _RUST_PLACE.sub("", str(exc.__cause__ or exc)).strip()
        raise PlanError(f"--join: cannot reach the router at {plan.endpoint}: {reason}") \
            from exc


_RUST_PLACE = re.compile(r"\s+at \S+\.rs:\d+\.?$")
"""Where in zenoh's Rust source an error was raised, at the end of its message."""


def _check_run_id(run: str, given_by: str) -> None:
    """Refuse a run id that cannot be a bus key's chunk, naming where it came from (`--run`,
    or the scenario's `[run].name`, which the scenario check refuses first)."""
    from bus.errors import KeyFormatError
    from bus.keys import check_chunk

    try:
        check_chunk(run, "run id")
    except KeyFormatError as exc:
        raise PlanError(f"{given_by}: {exc}") from exc


def _echo_joined(plan: Plan, outcome: Outcome) -> None:
    click.echo(f"left run {plan.run}: {', '.join(plan.local)} stopped")
    if outcome.ended:
        click.echo(f"  {outcome.ended}")
    shown = {n: k for n, k in outcome.restarts.items() if k}
    click.echo(f"  restarts: {sum(shown.values())}"
               + (f" ({', '.join(f'{n} {k}' for n, k in shown.items())})" if shown else ""))
    for name in outcome.left_down:
        click.echo(f"  failed: {name} gave up")


commands = [launch]


def wait_for_run_file(timeout: float, run: str | None = None) -> runfile.RunInfo:
    """For tests and scripts: the running launch once it is registered."""
    end = time.monotonic() + timeout
    while True:
        try:
            return runfile.find(run)
        except runfile.NoRunningLaunch:
            if time.monotonic() > end:
                raise
            time.sleep(0.05)

