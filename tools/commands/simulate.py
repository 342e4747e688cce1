"""`teleo simulate SCENARIO`: the whole cognitive cycle in one process, without the bus.

The cycle of a launch's world (world/cycle.py's CycleRunner) with the agents in this process
(tools/commands/sim_agents.py): the same pure pieces the processes run (the world, its
perception, the language engine), with the memory round trip of the bus. It is what a program
author iterates with, and what the driving program's tests run: a lockstep run over the bus
gives the same trace cycle for cycle, since each stage is a pure function of its inputs.
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from agents.lang import Engine, EngineState, LangError, load_program
from agents.lang.loader import read_text
from agents.lang.registry import learned_text, read_learned
from bus.collector import Collector
from bus.cycle import CycleReport
from tools.commands.examples import ScenarioArg
from tools.commands.plot import plot_check
from tools.commands.scenario_check import check_learned, load_checked, override_option
from tools.commands.sim_agents import AgentCycle, InProcessAgents, SimRun
from tools.launching.progress import progress_cycles
from tools.paths import OutputPath, picture_check
from tools.records import run_status, sim_summary, summary
from world.cycle import CycleRunner, CycleState
from world.domain import get_domain
from world.errors import WorldError
from world.run_scenario import Scenario, ScenarioError

log = logging.getLogger(__name__)
__all__ = ["AgentCycle", "SimRun", "simulate", "simulate_command", "write_learned"]


def simulate(scenario: Scenario, cycles: int | None = None, seed: int | None = None,
             keep_every: int = 0, learned: Path | None = None, recorder: Any = None,
             show_progress: bool = False,
             until: Callable[[dict[str, EngineState]], bool] | None = None) -> SimRun:
    """Run `cycles` cycles of `scenario` in this process; keep every `keep_every`-th snapshot;
    every agent starts from the skills in the learned file `learned` (raises LangError with
    file:line:col if it does not fit an agent's program); `recorder` (a SimRecorder,
    tools/records/run_recorders.py) gets every cycle's messages; `show_progress`: a progress
    bar on a terminal (tools/launching/progress.py); `until`: stop after the first cycle at whose
    end it answers True for the agents' states (a benchmark's run ends when its work is done).
    The garbage collector runs as in a stage process: between cycles (bus/collector.py)."""
    collector = Collector()
    try:
        return _cycles(scenario, cycles, seed, keep_every, learned, recorder, show_progress,
                       until, collector)
    finally:
        collector.close()


def _cycles(scenario: Scenario, cycles: int | None, seed: int | None, keep_every: int,
            learned: Path | None, recorder: Any, show_progress: bool,
            until: Callable[[dict[str, EngineState]], bool] | None,
            collector: Collector) -> SimRun:
    agents = scenario.agent_ids
    domain = get_domain(scenario.domain)
    sim = domain.create(scenario.world_table, scenario.run.seed if seed is None else seed, agents)
    programs = {a.id: load_program(a.program) for a in scenario.agents}
    engines = {a.id: Engine(programs[a.id], solver=a.impasse_handler) for a in scenario.agents}
    text = read_text(learned) if learned else ""
    states = {a: engines[a].initial_state(learned=read_learned(programs[a], text, str(learned))
                                          if learned else ()) for a in agents}
    run = SimRun()
    runner = CycleRunner(sim, agents, scenario.events)
    team = InProcessAgents(scenario, engines, states, domain, run, runner.static, recorder)
    if recorder is not None:
        recorder.static(domain.name, runner.static)   # as a launch's world: once
    total = scenario.run.cycles if cycles is None else cycles
    start = time.monotonic()
    for cycle in progress_cycles(total, show_progress):
        done = runner.cycle(cycle, _Told(team, recorder))
        if keep_every and cycle % keep_every == 0:
            run.snapshots.append(done.snap)
        run.trace.append(done.trace())
        if recorder is not None:
            recorder.world_stats(cycle, done.world_ms)
        collector.after_cycle()
        if done.over or (until is not None and until(states)):
            break
    run.final = sim.snapshot_dict()
    run.learned = {a: states[a].learned for a in agents}
    run.states = states
    run.goals, run.elapsed_s = team.goals.store, time.monotonic() - start
    run.memory = {a: runner.memory.get(a, {}) for a in agents}
    return run


class _Told:
    """The in-process agents, with each world state told to the record first."""

    def __init__(self, team: InProcessAgents, recorder: Any) -> None:
        self.team, self.recorder = team, recorder

    def act(self, state: CycleState, snap: dict[str, Any]) -> CycleReport:
        if self.recorder is not None:
            self.recorder.world(state.t, state.snapshot, state.outcomes, state.events,
                                state.memory)
        return self.team.act(state, snap)


def write_learned(run: SimRun, scenario: Scenario, out: Path) -> list[Path]:
    """Write each agent's learned skills to `out` (one agent) or `out` with `-AGENT` before
    its suffix (several agents); returns the files written."""
    written = []
    for a in scenario.agents:
        path = out if len(scenario.agents) == 1 else out.with_name(f"{out.stem}-{a.id}"
                                                                  f"{out.suffix}")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(learned_text(run.learned[a.id], str(a.program)))
        written.append(path)
    return written


@click.command("simulate")
@click.argument("scenario", type=ScenarioArg())
@click.option("--cycles", type=click.IntRange(min=1), default=None,
              help="Cycles to run (default: the scenario's; one whose cycles = 0, a launch's "
                   "'until Ctrl-C', needs this).")
@click.option("--seed", type=int, default=None, help="World seed (default: the scenario's).")
@click.option("--trace", type=OutputPath(path_type=Path), default=None,
              help="Write the run's trace here: one JSON line per cycle, as a launch's "
                   "trace.jsonl (docs/scenarios.md, \"Run files\").")
@click.option("--render", type=OutputPath(picture_check, path_type=Path), default=None,
              help="Write a picture of the run (.png/.jpg: the last cycle, .gif: the run).")
@click.option("--learned", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=None, help="Start every agent from the skills in this learned file.")
@click.option("--learned-out", type=OutputPath(path_type=Path), default=None,
              help="Write the learned skills (those started from, then the new ones) here.")
@click.option("--plot", type=OutputPath(plot_check, path_type=Path), default=None,
              help="Write plots of the run record (PNG): speed, goal timeline, stage times.")
@click.option("--no-record", is_flag=True, help="Do not write the run record (record.mcap).")
@click.option("--summary", "summary_file", type=OutputPath(path_type=Path), default=None,
              help="Write the summary JSON here (the --json object), as a launch's --summary.")
@override_option
@click.option("--json", "as_json", is_flag=True,
              help="Print the summary as one JSON object (a launch's --json form) instead.")
def simulate_command(scenario: str, cycles: int | None, seed: int | None, trace: Path | None,
                     render: Path | None, learned: Path | None, learned_out: Path | None,
                     plot: Path | None, no_record: bool, summary_file: Path | None,
                     overrides: tuple[str, ...], as_json: bool) -> None:
    """Run SCENARIO in one process without the bus (to write programs).

    The same cycle as a lockstep launch, with the same goal ids (g1, g2, ...), trace lines
    and summary, with or without its record; a progress bar on a terminal. `--set
    KEY=VALUE` changes a field of the scenario for this run, as `teleo launch --set`."""
    from tools.records.run_recorders import SimRecorder

    recorder = None
    try:
        sc, _ = load_checked(scenario, overrides)
        if cycles is None and sc.run.cycles == 0:
            raise click.UsageError(f"{scenario}: cycles = 0 runs a launch until Ctrl-C; a "
                                   f"simulation needs a number: give --cycles N")
        if plot and no_record:
            raise click.UsageError("--plot draws the run record: leave out --no-record")
        if learned:
            check_learned(sc, str(learned))
        recorder = None if no_record else SimRecorder.create(sc)
        run = simulate(sc, cycles, seed, keep_every=sc.run.render_every if render else 0,
                       learned=learned, recorder=recorder, show_progress=True)
    except (ScenarioError, LangError, WorldError) as exc:
        raise click.ClickException(str(exc)) from exc
    finally:
        if recorder is not None:
            recorder.writer.close()
    notes = []
    if recorder is not None:
        notes.append(f"run record written to {recorder.writer.path}")
    if plot:
        from tools.commands.plot import plot_record

        notes.append(f"plot written to {plot_record(recorder.writer.path, plot)}")
    _write_outputs(run, sc, _Outputs(trace, render, learned_out, summary_file), seed, cycles,
                   as_json, notes, str(recorder.writer.path) if recorder else None)


@dataclass(frozen=True)
class _Outputs:
    """The files a simulate writes besides its record (None: not asked for)."""

    trace: Path | None
    render: Path | None
    learned_out: Path | None
    summary: Path | None


def _write_outputs(run: SimRun, sc: Scenario, out: _Outputs, seed: int | None,
                   cycles: int | None, as_json: bool, notes: list[str],
                   record: str | None) -> None:
    """The files asked for, then the summary (text, or JSON on stdout)."""
    trace, render, learned_out = out.trace, out.render, out.learned_out
    files = dict(zip(sc.agent_ids, write_learned(run, sc, learned_out), strict=False)) \
        if learned_out else {}
    if trace:
        trace.parent.mkdir(parents=True, exist_ok=True)
        trace.write_text("".join(run.trace))
        notes.append(f"trace written to {trace}")
    if render:
        render.parent.mkdir(parents=True, exist_ok=True)
        frames = get_domain(sc.domain).render(run.snapshots + [run.final], render,
                                              sc.agent_ids[0])
        notes.append(f"picture written to {render} ({frames} frame(s))")
    result = sim_summary.build(run, sc, sc.run.seed if seed is None else seed,
                               sc.run.cycles if cycles is None else cycles, trace, files)
    result["record"] = record
    if record is not None:   # the run id `teleo explain`, `view` and `plot` take (N11)
        result["run"] = Path(record).parent.name
    result["record_missing"] = None if record is None else 0  # written in the loop: all of it
    result["record_gaps"], result["record_failed"] = (None if record is None else []), None
    if out.summary:
        out.summary.parent.mkdir(parents=True, exist_ok=True)
        out.summary.write_text(json.dumps(result, indent=1))
        notes.append(f"summary written to {out.summary}")
    if as_json:
        click.echo(json.dumps(result, indent=1))
        for note in notes:
            click.echo(note, err=True)
    else:
        summary.echo(result)
        for note in notes:
            click.echo(note)
    raise SystemExit(run_status.exit_code(result))


commands = [simulate_command]
