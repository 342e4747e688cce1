"""`teleo simulate SCENARIO`: the whole cognitive cycle in one process, without the bus.

The same pure pieces the processes run (world.Simulation, world.driving.perception.perceive, the
language engine), called in the order of one cycle (DESIGN.md, "One cognitive cycle"). It is
what a program author iterates with, and what the driving program's tests run: a lockstep run
over the bus gives the same actions cycle for cycle, since each stage is a pure function of
its inputs.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import click

from agents.lang import Engine, EngineState, load_program
from tools.scenario_check import load_checked
from world.domain import get_domain
from world.run_scenario import Scenario, ScenarioError


@dataclass
class SimRun:
    """The outcome of an in-process run: per-cycle records, the kept snapshots and the final
    one (snapshot dicts of the scenario's domain, world/domain.py)."""

    records: list[dict[str, Any]] = field(default_factory=list)
    snapshots: list[dict[str, Any]] = field(default_factory=list)
    final: dict[str, Any] = field(default_factory=dict)


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


def simulate(scenario: Scenario, cycles: int | None = None, seed: int | None = None,
             keep_every: int = 0) -> SimRun:
    """Run `cycles` cycles of `scenario` in this process; keep every `keep_every`-th snapshot."""
    agents = scenario.agent_ids
    domain = get_domain(scenario.domain)
    sim = domain.create(scenario.world_table, scenario.run.seed if seed is None else seed, agents)
    engines = {a.id: Engine(load_program(a.program)) for a in scenario.agents}
    states = {a: engines[a].initial_state() for a in agents}
    run = SimRun()
    outcomes: dict[str, list[dict[str, Any]]] = {}
    total = scenario.run.cycles if cycles is None else cycles
    for cycle in range(total):
        for ev in scenario.events:
            if ev.at_cycle == cycle:
                sim.inject(ev.event)
        _apply_goals(scenario, cycle, engines, states)
        snap = sim.snapshot_dict()
        if keep_every and cycle % keep_every == 0:
            run.snapshots.append(snap)
        record: dict[str, Any] = {"cycle": cycle}
        for a in agents:
            result = engines[a].cycle(states[a], domain.perceive(snap, a),
                                      outcomes.get(a, ()))
            states[a] = result.state
            actions = [act.to_list() for act in result.decision.actions]
            outcomes[a] = sim.apply_actions(a, actions)
            record[a] = {"actions": actions,
                         "goals": [(g["id"], g["status"]) for g in
                                   result.decision.to_dict()["goals"]]}
        run.records.append(record)
        sim.step()
    run.final = sim.snapshot_dict()
    return run


@click.command("simulate")
@click.argument("scenario", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--cycles", type=int, default=None, help="Cycles to run (default: the scenario's).")
@click.option("--seed", type=int, default=None, help="World seed (default: the scenario's).")
@click.option("--trace", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write one JSON line per cycle (actions and goal statuses) to this file.")
@click.option("--render", type=click.Path(dir_okay=False, path_type=Path), default=None,
              help="Write a picture of the run (.png: the last cycle, .gif: the whole run).")
def simulate_command(scenario: Path, cycles: int | None, seed: int | None, trace: Path | None,
                     render: Path | None) -> None:
    """Run SCENARIO in one process, without the bus (for writing and debugging programs)."""
    try:
        sc, _ = load_checked(scenario)
    except ScenarioError as exc:
        raise click.ClickException(str(exc)) from exc
    run = simulate(sc, cycles, seed, keep_every=sc.run.render_every if render else 0)
    if trace:
        trace.parent.mkdir(parents=True, exist_ok=True)
        trace.write_text("".join(json.dumps(r) + "\n" for r in run.records))
    if render:
        render.parent.mkdir(parents=True, exist_ok=True)
        get_domain(sc.domain).render(run.snapshots + [run.final], render, sc.agent_ids[0])
    last = run.records[-1] if run.records else {}
    click.echo(json.dumps({"cycles": len(run.records), "time": run.final.get("time"),
                           "counters": run.final.get("counters", {}),
                           "goals": {a: last.get(a, {}).get("goals", []) for a in sc.agent_ids}}))


commands = [simulate_command]
