"""`teleo launch SCENARIO`: start every process of a scenario, supervise, stop, summarise.

Order of a launch: a router (bus.router.spawn_router), then the goal-entry process, each
agent's perception, inference and executive, and the world (the clock, which waits for all
the others). The launcher waits until every process has announced itself (liveliness), shows
their status, restarts a crashed one per its respawn policy, and when the world finishes its
cycles (or on Ctrl-C) stops them in order: world, executives, inferences, perceptions, goals,
router. It writes a run file (tools/runfile.py) so `teleo goal` and `teleo inspect` find it.
"""

from __future__ import annotations

import json
import logging
import os
import secrets
import signal
import time
from dataclasses import replace
from pathlib import Path

import click

from tools import runfile, summary
from tools.scenario_check import load_checked
from tools.supervisor import ProcSpec, Supervisor, module_argv
from world.run_scenario import AGENT_STAGES, Scenario, ScenarioError

log = logging.getLogger(__name__)
READY_TIMEOUT = 60.0  # [s] for every process to announce itself (imports + zenoh open)


def process_specs(scenario: Scenario, run: str, run_dir: Path, bus_args: list[str],
                  cycles: int, seed: int, mode: str, learned: str | None = None
                  ) -> list[ProcSpec]:
    """The command of every process of the run, in start order (world last). Each executive
    keeps its engine state and learned skills in the run folder (summary.state_file,
    summary.learned_file), starting from ``learned`` if given."""
    common = ["--run", run, *bus_args]
    specs = [ProcSpec("goals", module_argv(
        "agents.processes.goals", *common, "--scenario", str(scenario.path),
        "--store", str(run_dir / summary.GOALS_FILE)), scenario.run.goals_respawn)]
    modules = {"perception": "agents.processes.perception",
               "inference": "agents.processes.inference",
               "executive": "agents.processes.executive"}
    for agent in scenario.agents:
        for stage in AGENT_STAGES:
            extra = [] if stage == "perception" else ["--program", str(agent.program)]
            if stage == "executive":
                extra += ["--state", str(summary.state_file(run_dir, agent.id)),
                          "--learned-out", str(summary.learned_file(run_dir, agent.id)),
                          *(["--learned", learned] if learned else []),
                          *([] if agent.solver else ["--no-solver"]),
                          *(["--mechanism", agent.mechanism]
                            if agent.mechanism != "means-ends" else [])]
            specs.append(ProcSpec(f"{agent.id}.{stage}", module_argv(
                modules[stage], *common, "--agent", agent.id, *extra),
                agent.max_restarts(stage)))
    specs.append(ProcSpec("world", module_argv(
        "world.process", *common, "--scenario", str(scenario.path), "--cycles", str(cycles),
        "--seed", str(seed), "--run-mode", mode, "--out", str(run_dir)), 0))
    return specs


def stop_order(scenario: Scenario) -> list[str]:
    """World first (it is the clock), then each stage kind from the last to the first."""
    names = ["world"]
    for stage in reversed(AGENT_STAGES):
        names += [f"{a.id}.{stage}" for a in scenario.agents]
    return names + ["goals"]


def check_learned(scenario: Scenario, learned: str) -> None:
    """Refuse a learned file that does not fit every agent's program, before any process
    starts (the message names file:line:col, e.g. a concept the program does not define)."""
    from agents.lang import LangError, load_program
    from agents.lang.loader import read_text
    from agents.lang.solving.learned import read_learned

    try:
        text = read_text(learned)
        for agent in scenario.agents:
            read_learned(load_program(agent.program), text, learned)
    except LangError as exc:
        raise click.ClickException(str(exc)) from exc


def _raise_interrupt(signum: int, frame: object) -> None:
    raise KeyboardInterrupt


@click.command()
@click.argument("scenario_file", metavar="SCENARIO", type=click.Path(dir_okay=False))
@click.option("--cycles", type=click.IntRange(min=0), help="Cycles to run (0: forever).")
@click.option("--seed", type=int, help="World seed (overrides [run].seed).")
@click.option("--mode", type=click.Choice(["lockstep", "realtime"]), help="Clock mode.")
@click.option("--summary", "summary_file", type=click.Path(dir_okay=False),
              help="Write the summary JSON here.")
@click.option("--render", "render_file", type=click.Path(dir_okay=False),
              help="Draw the run: a .png of the last state or a .gif of the run.")
@click.option("--learned", type=click.Path(exists=True, dir_okay=False),
              help="Start every agent from the skills learned in an earlier run (its "
                   "learned-AGENT.tlp); the run's own file holds them plus the new ones.")
@click.option("--plot", "plot_file", type=click.Path(dir_okay=False),
              help="Plot the run record (PNG): speed, goal timeline, stage times.")
@click.option("--no-record", is_flag=True, help="Do not write the run record (record.mcap).")
def launch(scenario_file: str, cycles: int | None, seed: int | None, mode: str | None,
           summary_file: str | None, render_file: str | None, learned: str | None,
           plot_file: str | None, no_record: bool) -> None:
    """Start every process of SCENARIO, supervise them, and summarise the run."""
    try:
        scenario, _ = load_checked(scenario_file)
    except ScenarioError as exc:
        raise click.ClickException(str(exc)) from exc
    if learned:
        check_learned(scenario, learned)
    cycles = scenario.run.cycles if cycles is None else cycles
    seed = scenario.run.seed if seed is None else seed
    mode = mode or scenario.run.mode.value
    run = f"{scenario.run.name}-{secrets.token_hex(3)}"
    run_dir = runfile.base_dir() / "runs" / run
    base = {"run": run, "scenario": str(scenario.path), "mode": mode, "seed": seed,
            "cycles_requested": cycles}
    signal.signal(signal.SIGTERM, _raise_interrupt)
    restarts = _run(scenario, run, run_dir, cycles, seed, mode, learned,
                    record=not no_record or bool(plot_file))
    result = summary.build(run_dir, base, restarts, scenario.domain)
    summary.echo(result)
    if summary_file:
        Path(summary_file).parent.mkdir(parents=True, exist_ok=True)
        Path(summary_file).write_text(json.dumps(result, indent=1))
        click.echo(f"summary written to {summary_file}")
    if render_file:
        frames = summary.render(run_dir, Path(render_file), scenario.agent_ids[0])
        click.echo(f"picture written to {render_file} ({frames} frame(s))" if frames
                   else "no snapshots saved: nothing rendered")
    if plot_file:
        from tools.plot import plot_command_output

        click.echo(plot_command_output(run_dir, Path(plot_file)))
    if not result["completed"]:
        raise SystemExit(1)


def _run(scenario: Scenario, run: str, run_dir: Path, cycles: int, seed: int,
         mode: str, learned: str | None, record: bool = True) -> dict[str, int]:
    """Start, supervise and stop the processes; returns restarts per process."""
    from bus.config import BusConfig
    from bus.router import spawn_router
    from tools.recorder import start_run_recorder

    run_dir.mkdir(parents=True, exist_ok=True)
    router = spawn_router()
    cfg = BusConfig(connect=(router.endpoint,))
    recorder = start_run_recorder(cfg, run, run_dir, scenario) if record else None
    sup = Supervisor(run_dir / "logs")
    info = runfile.RunInfo(run, router.endpoint, os.getpid(), tuple(scenario.agent_ids),
                           str(run_dir), str(scenario.path))
    try:
        for spec in process_specs(scenario, run, run_dir, cfg.to_args(), cycles, seed, mode,
                                  learned):
            sup.start(spec)
        click.echo(f"run {run}: {len(sup.names())} processes, router {router.endpoint}, "
                   f"logs in {run_dir / 'logs'}")
        _supervise(sup, cfg, info)
    except KeyboardInterrupt:
        click.echo("interrupted: stopping the run")
    finally:
        sup.stop_all(stop_order(scenario))
        if recorder is not None:
            recorder.stop()
        router.stop()
        runfile.remove(info)
    return sup.restarts()


def _supervise(sup: Supervisor, cfg, info: runfile.RunInfo) -> None:
    """Wait for every announcement, publish the run file, then restart crashed processes
    until the world ends."""
    from bus.node import open_node

    with open_node(cfg, info.run, "launch") as node:
        _wait_ready(sup, node, Path(info.run_dir) / "logs")
        _show_status(sup, node.alive())
        _publish_run_file(sup, info)
        while True:
            exits = sup.poll(exempt=("world",))
            if any(ex.restarted for ex in exits):
                _publish_run_file(sup, info)
            for ex in exits:
                if ex.name == "world":
                    if ex.returncode != 0:
                        click.echo(f"world exited with code {ex.returncode}", err=True)
                    return
                verb = f"restarted ({ex.restarts})" if ex.restarted else "left down"
                click.echo(f"{ex.name} exited with code {ex.returncode}: {verb}", err=True)
            node.presence.wait_change(0.2)


def _wait_ready(sup: Supervisor, node, log_dir: Path) -> None:
    """Wait until every process has announced itself; fail fast, with the end of its log,
    when one exits during start-up."""
    expected = set(sup.names())
    end = time.monotonic() + READY_TIMEOUT
    while not expected <= node.alive():
        for ex in sup.poll():
            tail = _log_tail(log_dir / f"{ex.name}.log")
            raise click.ClickException(f"{ex.name} exited with code {ex.returncode} while "
                                       f"starting; end of its log:\n{tail}")
        if time.monotonic() > end:
            missing = sorted(expected - node.alive())
            raise click.ClickException(f"not every process announced itself within "
                                       f"{READY_TIMEOUT:g} s: missing {missing}; see {log_dir}")
        node.presence.wait_change(0.1)


def _log_tail(path: Path, lines: int = 12) -> str:
    try:
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:])
    except FileNotFoundError:
        return "(no log)"


def _publish_run_file(sup: Supervisor, info: runfile.RunInfo) -> None:
    runfile.write(replace(info, pids={name: sup.pid(name) for name in sup.names()}))


def _show_status(sup: Supervisor, alive: set[str]) -> None:
    for name in sup.names():
        state = "up" if name in alive else ("running" if sup.running(name) else "exited")
        click.echo(f"  {name:<24} pid {sup.pid(name):<8} {state}")


commands = [launch]


def wait_for_run_file(timeout: float) -> runfile.RunInfo:
    """For tests and scripts: the running launch once its run file appears."""
    end = time.monotonic() + timeout
    while True:
        try:
            return runfile.find()
        except runfile.NoRunningLaunch:
            if time.monotonic() > end:
                raise
            time.sleep(0.05)
