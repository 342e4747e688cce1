"""Several agents' stages in one process (`teleo launch --agents-per-process K`).

    python -m agents.processes.shared --run RUN --name agents1 --agents JSON [bus flags]

JSON: a list of {"agent", "program", "state", "learned_out", "learned", "solver",
"mechanism", "swapped"} (AgentSetup.to_json: the executive's options;
tools/launching/run_plan.py writes them). Each cycle the
process joins the world state with every agent's goal list and runs, per agent, the perception,
inference and executive steps of the separate processes (the same functions) one after the
other, handing each step's message to the next in memory: no hop, no decode between an
agent's stages. Perception and inference need only the world state: when it arrives before the
goal lists (the goal-entry process sends them once it has the state), they run at once, so
the goal-entry process's work and hop overlap the agents' (bus/stage.py `early`).
It still publishes every message (percepts, beliefs, intention, actions), each stage's stats
carried in its outputs as a separate stage's are (bus/stats.py; sent alone by the Stage once
idle after a cycle, under each stage's own name), and announces each stage, so the clock,
the recorder and the inspector see the usual processes. Two or more cores then serve fewer
processes: fewer wake-ups per cycle and one interpreter's memory for several agents.
"""

from __future__ import annotations

import json
import logging
import time
from dataclasses import replace

import click

from agents.lang import LangError
from agents.processes import executive, inference, perception
from agents.processes.agent_setup import AgentSetup
from agents.processes.common import setup_logging, stop_on_signals
from bus import keys
from bus.config import BusConfig, bus_options
from bus.errors import Refused
from bus.messages import Actions, Message
from bus.node import open_node
from bus.rows import shared_rows
from bus.stage import Stage

STAGE_NAMES = ("perception", "inference", "executive")


class Chain:
    """One agent's three steps in turn: `front` (perception, inference: the world state is
    all they need) and `step` (the executive too, once the goal list is there), handing each
    step's message to the next in memory."""

    def __init__(self, setup: AgentSetup, log: logging.Logger,
                 static: perception.StaticSource | None = None) -> None:
        run, agent = setup.run, setup.agent
        self.names = [setup.process(s) for s in STAGE_NAMES]
        self.run, self.agent = run, agent
        self.perceive = perception.make_step(setup, static)
        self.infer = inference.make_step(setup, log)
        self.decide = executive.make_step(setup, log)
        self.keys = (keys.percepts(run, agent), keys.beliefs(run, agent),
                     keys.goal_list(run, agent))
        self.ahead: tuple[int, list, list, dict] | None = None  # front, done early

    def front(self, cycle: int, inputs: dict[str, Message]) -> tuple[list, list, dict]:
        """Percepts and beliefs of `cycle`, each carrying its stage's stats as a stage's
        output does (bus/stats.py), and those stats (process -> [compute_ms, late])."""
        t0 = time.perf_counter()
        p_out = self.perceive(cycle, inputs)
        seen = p_out[0][1]  # rows as a receiver on the bus would get them (bus/rows.py)
        rows = shared_rows("Percepts", self.agent, seen.percepts)
        t1 = time.perf_counter()
        stats = {self.names[0]: [(t1 - t0) * 1e3, 0]}
        p_out[0] = (p_out[0][0], replace(seen, percepts=rows, stats=dict(stats)))
        t2 = time.perf_counter()
        b_out = self.infer(cycle, {self.keys[0]: p_out[0][1]})
        stats[self.names[1]] = [(time.perf_counter() - t2) * 1e3, 0]
        b_out[0] = (b_out[0][0], replace(b_out[0][1], stats=dict(stats)))
        return p_out, b_out, stats

    def early(self, cycle: int, state_key: str, state: Message) -> None:
        """`front` of `cycle` now, while the goal lists are on the way (once a cycle)."""
        if self.ahead is None or self.ahead[0] < cycle:
            try:
                self.ahead = (cycle, *self.front(cycle, {state_key: state}))
            except Refused:   # the step, run again on the complete cycle, refuses it
                self.ahead = None

    def step(self, cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        """Every output of `cycle`: percepts, beliefs, intention, actions; the actions carry
        the stats of the agent's whole pipeline, the goal entry's included (from its list)."""
        if self.ahead is not None and self.ahead[0] == cycle:
            p_out, b_out, stats = self.ahead[1:]
        else:
            p_out, b_out, stats = self.front(cycle, inputs)
        if self.ahead is not None and self.ahead[0] <= cycle:
            self.ahead = None
        p_key, b_key, g_key = self.keys
        goals = inputs[g_key]
        t2 = time.perf_counter()
        e_out = self.decide(cycle, {p_key: p_out[0][1], b_key: b_out[0][1], g_key: goals})
        ms = (time.perf_counter() - t2) * 1e3
        carried = {**goals.stats, **stats, self.names[2]: [ms, 0]}
        return [*p_out, *b_out, *((k, replace(m, stats=carried) if isinstance(m, Actions) else m)
                                  for k, m in e_out)]


def run_shared(cfg: BusConfig, run: str, name: str, specs: list[AgentSetup],
               log: logging.Logger) -> None:
    """Run the agents of `specs` in one Stage until SIGINT/SIGTERM."""
    static = perception.StaticSource(run, name)   # one ask for every agent here
    chains = [Chain(spec, log, static) for spec in specs]
    state_key = keys.world_state(run)

    made: list = [None, None]   # the last world state and its copy with the static part

    def whole(state: Message) -> Message:
        """`state` with its snapshot whole, made once for every agent here: their perception
        reads one dict, and the world checks it once (perception.with_static)."""
        if made[0] is not state:
            made[:] = [state, perception.with_static(state, static, state_key)]
        return made[1]

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        inputs = {**inputs, state_key: whole(inputs[state_key])}
        return [out for chain in chains for out in chain.step(cycle, inputs)]

    begun = [0, -1]   # cycles whose perception and inference ran before their goal lists,
                      # and the last of them

    def early(key: str, msg: Message) -> None:
        if key == state_key:
            try:
                state = whole(msg)
            except Refused:   # the step, run again on the complete cycle, refuses it
                return
            if msg.env.cycle > begun[1]:
                begun[:] = [begun[0] + 1, msg.env.cycle]
            for chain in chains:
                chain.early(msg.env.cycle, key, state)

    agents = [spec.agent for spec in specs]
    inputs = [state_key, *(keys.goal_list(run, a) for a in agents)]
    outputs = [keys.actions(run, a) for a in agents]
    stages = [f"{a}.{s}" for a in agents for s in STAGE_NAMES]
    stop = stop_on_signals()
    with open_node(cfg, run, name) as node:
        static.bind(node)
        stage = Stage(node, name, inputs, step, outputs=outputs, stages=stages, early=early)
        stage.start()
        log.info("announced %s; inputs %s", stages, inputs)
        stage.run(stop)
        log.info("stopped after %d cycles (%d late, %d begun before their goal lists)",
                 stage.cycles_done, stage.late, begun[0])


def read_setups(run: str, agents_json: str) -> list[AgentSetup]:
    """The agents of ``--agents``; a ClickException naming the item and key that is wrong."""
    try:
        items = json.loads(agents_json)
    except ValueError as exc:
        raise click.ClickException(f"--agents: not JSON: {exc}") from exc
    if not isinstance(items, list) or not items:
        raise click.ClickException(f"--agents: expected a non-empty JSON list of maps with "
                                   f"'agent' and 'program', got {agents_json:.80}")
    out = []
    for i, item in enumerate(items):
        try:
            out.append(AgentSetup.from_json(run, item))
        except ValueError as exc:
            raise click.ClickException(f"--agents[{i}]: {exc}") from exc
    return out


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--name", required=True, help="This process's name, e.g. agents1.")
@click.option("--agents", "agents_json", required=True,
              help="JSON list of the agents' specs (module docstring).")
@bus_options
def main(run: str, name: str, agents_json: str, bus_config: BusConfig) -> None:
    """Several agents' perception, inference and executive in one process."""
    log = setup_logging(name)
    specs = read_setups(run, agents_json)
    try:
        run_shared(bus_config, run, name, specs, log)
    except LangError as exc:
        raise click.ClickException(str(exc)) from exc

if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
