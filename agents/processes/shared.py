"""Several agents' stages in one process (`teleo launch --agents-per-process K`).

    python -m agents.processes.shared --run RUN --name agents1 --agents JSON [bus flags]

JSON: a list of {"agent", "program", "state", "learned_out", "learned", "solver",
"mechanism"} (the executive's options, tools/launching/run_plan.py writes them). Each cycle the
process joins the world state with every agent's goal list and runs, per agent, the perception,
inference and executive steps of the separate processes (the same functions) one after the
other, handing each step's message to the next in memory: no hop, no decode between an
agent's stages. It still publishes every message (percepts, beliefs, intention, actions) and
each stage's ProcessStats under the stage's own name, and announces each stage, so the clock,
the recorder and the inspector see the usual processes. Two or more cores then serve fewer
processes: fewer wake-ups per cycle and one interpreter's memory for several agents.
"""

from __future__ import annotations

import json
import logging
import time
from dataclasses import replace

import click

from agents.processes import executive, inference, perception
from agents.processes.common import setup_logging, stop_on_signals
from bus import keys
from bus.config import BusConfig, bus_options
from bus.messages import Envelope, Message, ProcessStats
from bus.rows import shared_rows

STAGE_NAMES = ("perception", "inference", "executive")


def make_chain(run: str, spec: dict, log: logging.Logger,
               static: perception.StaticSource | None = None):
    """step(cycle, {world state, goal list}) of one agent: its three steps in turn, their
    outputs and their ProcessStats (compute time of each step [ms])."""
    agent = spec["agent"]
    names = [f"{agent}.{s}" for s in STAGE_NAMES]
    perceive = perception.make_step(run, agent, names[0], static)
    infer = inference.make_step(run, agent, names[1], spec["program"], log)
    decide = executive.make_step(run, agent, names[2], spec["program"], log,
                                 spec.get("state"), spec.get("learned"),
                                 spec.get("learned_out"), spec.get("solver", True),
                                 spec.get("mechanism", "means-ends"))
    p_key, b_key, g_key = (keys.percepts(run, agent), keys.beliefs(run, agent),
                           keys.goal_list(run, agent))
    stats_keys = [keys.stats(run, n) for n in names]

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        t0 = time.perf_counter()
        p_out = perceive(cycle, inputs)
        seen = p_out[0][1]  # rows as a receiver on the bus would get them (bus/rows.py)
        p_out[0] = (p_out[0][0], replace(seen, percepts=shared_rows("Percepts", agent,
                                                                     seen.percepts)))
        t1 = time.perf_counter()
        b_out = infer(cycle, {p_key: p_out[0][1]})
        t2 = time.perf_counter()
        e_out = decide(cycle, {p_key: p_out[0][1], b_key: b_out[0][1], g_key: inputs[g_key]})
        t3 = time.perf_counter()
        stats = [(k, ProcessStats(Envelope.now(run, cycle, n), n, (b - a) * 1e3, 0))
                 for k, n, a, b in zip(stats_keys, names, (t0, t1, t2), (t1, t2, t3),
                                       strict=True)]
        return [*stats, *p_out, *b_out, *e_out]

    return step


def run_shared(cfg: BusConfig, run: str, name: str, specs: list[dict],
               log: logging.Logger) -> None:
    """Run the agents of `specs` in one Stage until SIGINT/SIGTERM."""
    from bus.node import open_node
    from bus.stage import Stage

    static = perception.StaticSource(run, name)   # one ask for every agent here
    chains = [make_chain(run, spec, log, static) for spec in specs]

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        return [out for chain in chains for out in chain(cycle, inputs)]

    agents = [spec["agent"] for spec in specs]
    inputs = [keys.world_state(run), *(keys.goal_list(run, a) for a in agents)]
    outputs = [keys.actions(run, a) for a in agents]
    stages = [f"{a}.{s}" for a in agents for s in STAGE_NAMES]
    stop = stop_on_signals()
    with open_node(cfg, run, name) as node:
        static.bind(node)
        stage = Stage(node, name, inputs, step, outputs=outputs, stages=stages)
        stage.start()
        log.info("announced %s; inputs %s", stages, inputs)
        stage.run(stop)
        log.info("stopped after %d cycles (%d late)", stage.cycles_done, stage.late)


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--name", required=True, help="This process's name, e.g. agents1.")
@click.option("--agents", "agents_json", required=True,
              help="JSON list of the agents' specs (module docstring).")
@bus_options
def main(run: str, name: str, agents_json: str, bus_config: BusConfig) -> None:
    """Several agents' perception, inference and executive in one process."""
    from agents.lang import LangError

    log = setup_logging(name)
    try:
        specs = json.loads(agents_json)
    except ValueError as exc:
        raise click.ClickException(f"--agents: not JSON: {exc}") from exc
    if not isinstance(specs, list) or not all(
            isinstance(s, dict) and {"agent", "program"} <= set(s) for s in specs):
        raise click.ClickException(f"--agents: expected a JSON list of maps with 'agent' and "
                                   f"'program', got {agents_json:.80}")
    try:
        run_shared(bus_config, run, name, specs, log)
    except LangError as exc:
        raise click.ClickException(str(exc)) from exc

if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
