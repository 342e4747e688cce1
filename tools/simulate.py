"""`teleo simulate SCENARIO`: the whole cognitive cycle in one process, without the bus.

The same pure pieces the processes run (world.Simulation, world.driving.perception.perceive, the
language engine), called in the order of one cycle (DESIGN.md, "One cognitive cycle"). It is
what a program author iterates with, and what the driving program's tests run: a lockstep run
over the bus gives the same actions cycle for cycle, since each stage is a pure function of
its inputs.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import click

from agents.lang import Engine, EngineState, LangError, load_program
from agents.lang.loader import read_text
from agents.lang.solving.learned import clause_heads, learned_text, read_learned
from tools.scenario_check import load_checked
from world.domain import get_domain
from world.run_scenario import Scenario, ScenarioError


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


def _apply_goals(scenario: Scenario, cycle: int, engines: dict[str, Engine],
                 states: dict[str, EngineState]) -> None:
    for k, g in enumerate(scenario.goals):
        if g.at_cycle != cycle:
            continue
        engine, state = engines[g.agent], states[g.agent]
        goal_id = g.goal_id or f"s{k + 1}"
        if g.op == "post":
            states[g.agent] = engine.add_goal(state, g.goal, priority=g.priority, goal_id=goal_id)
        elif g.op == "cancel":
            states[g.agent] = engine.remove_goal(state, goal_id)
        else:
            states[g.agent] = engine.set_priority(state, goal_id, g.priority)


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
    beliefs = engine.infer(percepts, state.scs.model)  # as Engine.cycle does
    t2 = time.perf_counter()
    decision, state = engine.decide(state, percepts, beliefs, outcomes)
    t3 = time.perf_counter()
    ms = {"perception": (t1 - t0) * 1e3, "inference": (t2 - t1) * 1e3,
          "executive": (t3 - t2) * 1e3}
    return AgentCycle(percepts, list(outcomes), beliefs, decision, ms), state


def simulate(scenario: Scenario, cycles: int | None = None, seed: int | None = None,
             keep_every: int = 0, learned: Path | None = None, recorder: Any = None) -> SimRun:
    """Run `cycles` cycles of `scenario` in this process; keep every `keep_every`-th snapshot;
    every agent starts from the skills in the learned file `learned` (raises LangError with
    file:line:col if it does not fit an agent's program); `recorder` (a
    tools.recorder.SimRecorder) gets every cycle's messages."""
    agents = scenario.agent_ids
    domain = get_domain(scenario.domain)
    sim = domain.create(scenario.world_table, scenario.run.seed if seed is None else seed, agents)
    programs = {a.id: load_program(a.program) for a in scenario.agents}
    engines = {a.id: Engine(programs[a.id], solver=a.impasse_handler) for a in scenario.agents}
    text = read_text(learned) if learned else ""
    states = {a: engines[a].initial_state(learned=read_learned(programs[a], text, str(learned))
                                          if learned else ()) for a in agents}
    run = SimRun()
    outcomes: dict[str, list[dict[str, Any]]] = {}
    total = scenario.run.cycles if cycles is None else cycles
    for cycle in range(total):
        w0 = time.perf_counter()
        injected = [sim.inject(ev.event) for ev in scenario.events if ev.at_cycle == cycle]
        _apply_goals(scenario, cycle, engines, states)
        snap = sim.snapshot_dict()
        if keep_every and cycle % keep_every == 0:
            run.snapshots.append(snap)
        if recorder is not None:
            recorder.world(cycle, snap, {a: outcomes.get(a, []) for a in agents}, injected)
        world_ms = (time.perf_counter() - w0) * 1e3
        record: dict[str, Any] = {"cycle": cycle}
        for a in agents:
            seen, states[a] = _agent_cycle(engines[a], states[a], domain, snap, a,
                                           outcomes.get(a, []))
            actions = [act.to_list() for act in seen.decision.actions]
            w0 = time.perf_counter()
            outcomes[a] = sim.apply_actions(a, actions)
            world_ms += (time.perf_counter() - w0) * 1e3
            record[a] = {"actions": actions,
                         "goals": [(g.id, g.status.value) for g in seen.decision.goals]}
            for name in ("solver", "planner"):
                section = seen.decision.section(name)
                if section is not None:
                    record[a][name] = section.to_dict()
            if recorder is not None:
                recorder.agent(cycle, a, seen)
        run.records.append(record)
        w0 = time.perf_counter()
        sim.step()
        if recorder is not None:
            recorder.world_stats(cycle, world_ms + (time.perf_counter() - w0) * 1e3)
    run.final = sim.snapshot_dict()
    run.learned = {a: states[a].learned for a in agents}
    run.states = states
    return run


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
@click.argument("scenario", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--cycles", type=int, default=None, help="Cycles to run (default: the scenario's).")
@click.option("--seed", type=int, default=None, help="World seed (default: the scenario's).")
@click.option("--trace", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write one JSON line per cycle (actions and goal statuses) to this file.")
@click.option("--render", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write a picture of the run (.png: the last cycle, .gif: the whole run).")
@click.option("--learned", type=click.Path(exists=True, dir_okay=False, path_type=Path),
              default=None, help="Start every agent from the skills in this learned file.")
@click.option("--learned-out", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write the learned skills (those started from, then the new ones) here.")
@click.option("--plot", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write plots of the run record (PNG): speed, goal timeline, stage times.")
@click.option("--no-record", is_flag=True, help="Do not write the run record (record.mcap).")
def simulate_command(scenario: Path, cycles: int | None, seed: int | None, trace: Path | None,
                     render: Path | None, learned: Path | None, learned_out: Path | None,
                     plot: Path | None, no_record: bool) -> None:
    """Run SCENARIO in one process, without the bus (for writing and debugging programs)."""
    from tools.recorder import SimRecorder

    recorder = None
    try:
        sc, _ = load_checked(scenario)
        recorder = None if no_record and not plot else SimRecorder.create(sc)
        run = simulate(sc, cycles, seed, keep_every=sc.run.render_every if render else 0,
                       learned=learned, recorder=recorder)
    except (ScenarioError, LangError) as exc:
        raise click.ClickException(str(exc)) from exc
    finally:
        if recorder is not None:
            recorder.writer.close()
    if plot:
        from tools.plot import plot_record

        click.echo(f"plot written to {plot_record(recorder.writer.path, plot)}", err=True)
    if learned_out:
        write_learned(run, sc, learned_out)
    if trace:
        trace.parent.mkdir(parents=True, exist_ok=True)
        trace.write_text("".join(json.dumps(r) + "\n" for r in run.records))
    if render:
        render.parent.mkdir(parents=True, exist_ok=True)
        get_domain(sc.domain).render(run.snapshots + [run.final], render, sc.agent_ids[0])
    last = run.records[-1] if run.records else {}
    click.echo(json.dumps({"cycles": len(run.records), "time": run.final.get("time"),
                           "counters": run.final.get("counters", {}),
                           "goals": {a: last.get(a, {}).get("goals", []) for a in sc.agent_ids},
                           "learned": {a: clause_heads("\n".join(run.learned[a]))
                                       for a in sc.agent_ids},
                           "record": str(recorder.writer.path) if recorder else None}))


commands = [simulate_command]
