"""`teleo simulate SCENARIO`: the whole cognitive cycle in one process, without the bus.

The same pure pieces the processes run (world.Simulation, world.driving.perception.perceive, the
language engine), called in the order of one cycle (DESIGN.md, "One cognitive cycle"). It is
what a program author iterates with, and what the driving program's tests run: a lockstep run
over the bus gives the same actions cycle for cycle, since each stage is a pure function of
its inputs.
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import click

from agents.lang import Engine, EngineState, LangError, load_program
from agents.lang.loader import read_text
from agents.lang.registry import learned_text, memory_of, read_learned
from agents.processes.goal_store import GoalStore, GoalStoreError, refused_text
from agents.processes.goal_sync import GoalSync, validator
from agents.processes.hints import with_hints
from bus.collector import Collector
from tools.commands.examples import ScenarioArg
from tools.commands.plot import plot_check
from tools.commands.scenario_check import check_learned, load_checked, override_option
from tools.launching.progress import progress_cycles
from tools.paths import OutputPath, picture_check
from tools.records import sim_summary, summary
from tools.records.run_record import GoalHistory
from world.domain import episode_over, get_domain
from world.errors import WorldError
from world.run_scenario import Scenario, ScenarioError, ScriptedGoal
from world.static import split, whole
from world.trace import trace_line

log = logging.getLogger(__name__)


@dataclass
class SimRun:
    """The outcome of an in-process run: per-cycle records, the kept snapshots and the final
    one (snapshot dicts of the scenario's domain, world/domain.py), each agent's learned
    skills at the end (EngineState.learned: the ones it started from, then the new ones) and
    its engine state at the end (``states``: the planner's head-plan, for one)."""

    records: list[dict[str, Any]] = field(default_factory=list)
    snapshots: list[dict[str, Any]] = field(default_factory=list)
    final: dict[str, Any] = field(default_factory=dict)
    learned: dict[str, tuple[str, ...]] = field(default_factory=dict)
    states: dict[str, EngineState] = field(default_factory=dict)
    trace: list[str] = field(default_factory=list)   # trace.jsonl lines (world/trace.py)
    goals: GoalStore = field(default_factory=GoalStore)  # user goals, as a launch keeps them
    memory: dict[str, dict[str, Any]] = field(default_factory=dict)  # each agent's, at the end
    history: GoalHistory = field(default_factory=GoalHistory)  # each goal's changes
    elapsed_s: float = 0.0


class _Goals:
    """The user goals of a simulated run, kept as the goal-entry process keeps them: the
    scenario's requests applied to a GoalStore at their cycle (ids g1, g2, ... in order),
    statuses mirrored from each decision, and each engine's goals synced from the store's goal
    list (agents/processes/goal_sync.py), so ids, statuses and the goals the engine is given
    are those of `teleo launch`."""

    def __init__(self, scenario: Scenario, engines: dict[str, Engine]) -> None:
        self.scenario = scenario
        self.engines = engines
        self.store = GoalStore()
        self.validate = validator(engines)
        self.sync = {a: GoalSync() for a in engines}

    def before(self, cycle: int, states: dict[str, EngineState],
               history: GoalHistory) -> None:
        """Apply the requests due at ``cycle``, then give each engine its goal list (told to
        ``history`` as the record is told the goal-entry process's GoalList)."""
        for g in self.scenario.goals:
            if g.at_cycle == cycle:
                self.store = _request(self.store, g, cycle, self.validate)
        for a, engine in self.engines.items():
            listed = self.store.goal_list(a)
            history.feed({"kind": "GoalList", "agent": a, "env": {"cycle": cycle},
                          "goals": list(listed)})
            states[a] = self.sync[a].apply(engine, states[a], listed, log)

    def after(self, agent: str, decision: dict[str, Any], cycle: int) -> None:
        """Mirror the statuses the agent's decision of ``cycle`` reports."""
        self.store = self.store.update_from_intention(agent, decision, cycle)


def _request(store: GoalStore, g: ScriptedGoal, cycle: int, validate) -> GoalStore:
    """One scripted request applied to ``store`` (a refused one is logged, as the goal-entry
    process logs it)."""
    try:
        if g.op == "post":
            return store.post(g.agent, g.goal, g.priority, cycle, validate, g.once,
                              g.deadline)[0]
        if g.op == "cancel":
            return store.cancel(g.goal_id, cycle, g.force)
        return store.set_priority(g.goal_id, g.priority, cycle)
    except GoalStoreError as exc:
        log.info("scripted request refused: %s", exc)   # the summary says it
        return store.refusing(refused_text(g.op, g.goal_id, g.goal, cycle, exc))


@dataclass(frozen=True)
class AgentCycle:
    """What one agent saw and did in one cycle, for a recorder (tools/recorder.SimRecorder);
    ms: compute time per stage [ms]."""

    percepts: list
    outcomes: list
    beliefs: Any
    decision: Any
    ms: dict[str, float]


def _agent_cycle(engine: Engine, state: EngineState, domain: Any, snap: dict[str, Any],
                 agent: str, outcomes: list) -> tuple[AgentCycle, EngineState]:
    """Perception, inference and the executive step of one agent, each timed."""
    t0 = time.perf_counter()
    percepts = domain.perceive(snap, agent)
    t1 = time.perf_counter()
    beliefs = engine.infer(percepts, engine.facts(state))  # as Engine.cycle does
    t2 = time.perf_counter()
    decision, state = engine.decide(state, percepts, beliefs, outcomes)
    t3 = time.perf_counter()
    ms = {"perception": (t1 - t0) * 1e3, "inference": (t2 - t1) * 1e3,
          "executive": (t3 - t2) * 1e3}
    return AgentCycle(percepts, list(outcomes), beliefs, decision, ms), state


def simulate(scenario: Scenario, cycles: int | None = None, seed: int | None = None,
             keep_every: int = 0, learned: Path | None = None, recorder: Any = None,
             show_progress: bool = False,
             until: Callable[[dict[str, EngineState]], bool] | None = None) -> SimRun:
    """Run `cycles` cycles of `scenario` in this process; keep every `keep_every`-th snapshot;
    every agent starts from the skills in the learned file `learned` (raises LangError with
    file:line:col if it does not fit an agent's program); `recorder` (a
    tools.records.recorder.SimRecorder) gets every cycle's messages; `show_progress`: a progress
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
    goals = _Goals(scenario, engines)
    outcomes: dict[str, list[dict[str, Any]]] = {}
    memory: dict[str, dict[str, Any]] = {}   # each agent's last memory, as the world keeps it
    static: dict[str, Any] | None = None     # the world's static part, told once
    total = scenario.run.cycles if cycles is None else cycles
    start = time.monotonic()
    for cycle in progress_cycles(total, show_progress):
        w0 = time.perf_counter()
        injected = [sim.inject(ev.event) for ev in scenario.events if ev.at_cycle == cycle]
        goals.before(cycle, states, run.history)
        if recorder is not None:
            for a in agents:
                recorder.goal_list(cycle, a, goals.store.goal_list(a))
        snap = sim.snapshot_dict()
        over = episode_over(sim)   # this state is the episode's last: the run's last cycle
        if keep_every and cycle % keep_every == 0:
            run.snapshots.append(snap)
        told, moving = split(snap)   # as a launch's world: the static part once (issue 35)
        if static is None:
            static = told
            if recorder is not None:
                recorder.static(domain.name, static)
        if recorder is not None:
            recorder.world(cycle, moving, {a: outcomes.get(a, []) for a in agents}, injected,
                           memory)
        seen_snap = whole(static, moving)   # what a perception process puts together
        world_ms = (time.perf_counter() - w0) * 1e3
        record: dict[str, Any] = {"cycle": cycle}
        for a in agents:
            seen, states[a] = _agent_cycle(engines[a], states[a], domain, seen_snap, a,
                                           outcomes.get(a, []))
            actions = [act.to_list() for act in seen.decision.actions]
            w0 = time.perf_counter()
            outcomes[a] = sim.apply_actions(a, actions)
            world_ms += (time.perf_counter() - w0) * 1e3
            decided = seen.decision.to_dict()
            run.history.feed({"kind": "Intention", "agent": a, "env": {"cycle": cycle},
                              "decision": decided})
            goals.after(a, with_hints(decided, seen.percepts, programs[a]), cycle)
            record[a] = {"actions": actions,
                         "goals": [(g.id, g.status.value) for g in seen.decision.goals]}
            for name in ("solver", "planner"):
                section = seen.decision.section(name)
                if section is not None:
                    record[a][name] = section.to_dict()
            if recorder is not None:   # the memory a launch's messages carry
                recorder.agent(cycle, a, seen, memory.get(a, {}), _memory(states[a]))
        run.records.append(record)
        now = {a: _memory(states[a]) for a in agents}
        changed = {a: m for a, m in now.items() if memory.get(a, {}) != m}
        memory.update(changed)
        run.trace.append(trace_line(cycle, snap, {a: record[a]["actions"] for a in agents},
                                    injected, changed))
        w0 = time.perf_counter()
        sim.step()
        if recorder is not None:
            recorder.world_stats(cycle, world_ms + (time.perf_counter() - w0) * 1e3)
        collector.after_cycle()
        if over or (until is not None and until(states)):
            break
    run.final = sim.snapshot_dict()
    run.learned = {a: states[a].learned for a in agents}
    run.states = states
    run.goals, run.elapsed_s = goals.store, time.monotonic() - start
    run.memory = {a: memory.get(a, {}) for a in agents}
    return run


def _memory(state: EngineState) -> dict[str, Any]:
    """The agent memory an executive process would send last (docs/bus.md, "Agent memory")."""
    return memory_of(state)


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
    from tools.records.recorder import SimRecorder

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
    raise SystemExit(summary.exit_code(result))


commands = [simulate_command]
