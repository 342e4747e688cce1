"""The goal-entry process: users' goal requests in, one goal list per agent per cycle out.

    python -m agents.processes.goals --run RUN --scenario FILE --store FILE [bus flags]

It answers GoalRequests (post, cancel, priority, list) on teleo/<run>/agent/<agent>/goals at
any time, validating a post against the agent's program (Engine.add_goal: an unknown concept
or a wrong arity is refused with the engine's reason). When it sees the world state of cycle
t it applies the scenario's scripted requests of cycle t and publishes each agent's goal list
of t, the executive's goal input (a request received while running takes effect at the next
cycle it publishes). It reads the executives' intentions to keep each goal's status, and
saves the store after every change, so that a restart of any process loses no goal
(ROGUE, seed 003: asynchronous requests with priorities).
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import click

from agents.processes import goal_store
from agents.processes.common import setup_logging, stop_on_signals
from agents.processes.goal_store import GoalStore, GoalStoreError
from bus import keys
from bus.config import BusConfig, bus_options
from bus.messages import GoalList, GoalReply, GoalRequest, Intention, ProcessStats, WorldState
from bus.node import Node, open_node
from world.run_scenario import Scenario, ScriptedGoal, load_scenario

PROCESS = "goals"


def engine_validator(scenario: Scenario):
    """validate(agent, goal, priority) -> "" or the engine's reason, one Engine per agent."""
    from agents.lang import Engine, GoalError, load_program

    engines = {a.id: Engine(load_program(str(a.program))) for a in scenario.agents}

    def validate(agent: str, goal: str, priority: int) -> str:
        engine = engines[agent]
        try:
            engine.add_goal(engine.initial_state(), goal, priority=priority, goal_id="check")
        except GoalError as exc:
            return str(exc)
        return ""

    return validate


class GoalEntry:
    """The process's state: the store, its file, and the last goal lists published."""

    def __init__(self, scenario: Scenario, store_path: Path, validate, log) -> None:
        self.scenario = scenario
        self.path = store_path
        self.validate = validate
        self.log = log
        self.store = goal_store.load(store_path)
        self.lock = threading.Lock()  # the query handler runs on zenoh's thread
        self.cycle = -1
        self.published: dict[str, tuple[dict[str, Any], ...]] = {}
        self.node: Node | None = None  # set once the session is open

    def _set(self, store: GoalStore) -> None:
        if store != self.store:
            self.store = store
            goal_store.save(store, self.path)

    def handle(self, request: GoalRequest) -> GoalReply:
        """Answer one request (called on zenoh's callback thread)."""
        with self.lock:
            try:
                reason = self._apply(request.op, request.agent, request.goal, request.priority,
                                     request.goal_id, self.cycle + 1)
                ok = True
            except GoalStoreError as exc:
                reason, ok = str(exc), False
            goals = tuple(g.to_dict() for g in self.store.for_agent(request.agent))
            cycle = self.cycle
        self.log.info("%s %s %s -> %s", request.op, request.agent, request.goal or
                      request.goal_id, reason)
        return GoalReply(self.node.envelope(cycle), ok, reason, goals)

    def _apply(self, op: str, agent: str, goal: str, priority: int, goal_id: str,
               at: int) -> str:
        """Apply one request taking effect at cycle `at`; returns what was done."""
        if agent not in self.scenario.agent_ids:
            raise GoalStoreError(f"no agent {agent!r} in this run "
                                 f"(agents: {', '.join(self.scenario.agent_ids)})")
        if op == "post":
            store, record = self.store.post(agent, goal, priority, at, self.validate)
            self._set(store)
            return f"posted {record.id} for {agent}: {record.goal} (from cycle {at})"
        if op == "cancel":
            self._set(self.store.cancel(goal_id, at))
            return f"cancelled {goal_id} (from cycle {at})"
        if op == "priority":
            self._set(self.store.set_priority(goal_id, priority, at))
            return f"{goal_id} now has priority {priority} (from cycle {at})"
        if op == "list":
            return ""
        raise GoalStoreError(f"unknown op {op!r}: expected post, cancel, priority or list")

    def on_world_state(self, node: Node, cycle: int) -> None:
        """Apply the scripted requests due, then publish every agent's goal list of `cycle`.
        A repeated cycle (the clock re-sends it after a restart) gets the same lists again."""
        t0 = time.perf_counter()
        with self.lock:
            if cycle != self.cycle:
                self.cycle = cycle
                self._scripted(cycle)
                self.published = {a: self.store.goal_list(a) for a in self.scenario.agent_ids}
            lists = dict(self.published)
        # stats first: the clock names the first stage of a pipeline that has not reported
        node.publish(keys.stats(node.run, PROCESS), ProcessStats(
            node.envelope(cycle), PROCESS, (time.perf_counter() - t0) * 1e3, 0))
        for agent, goals in lists.items():
            node.publish(keys.goal_list(node.run, agent),
                         GoalList(node.envelope(cycle), agent, goals))

    def _scripted(self, cycle: int) -> None:
        due = [(i, g) for i, g in enumerate(self.scenario.goals)
               if g.at_cycle <= cycle and i not in self.store.scripted_done]
        for index, scripted in due:
            self._run_scripted(scripted)
            self._set(self.store.mark_scripted([index]))

    def _run_scripted(self, g: ScriptedGoal) -> None:
        try:
            reason = self._apply(g.op, g.agent, g.goal, g.priority, g.goal_id, self.cycle)
            self.log.info("scripted request at cycle %d: %s", self.cycle, reason)
        except GoalStoreError as exc:
            self.log.warning("scripted request refused: %s", exc)

    def on_intention(self, msg: Intention) -> None:
        with self.lock:
            self._set(self.store.update_from_intention(msg.agent, msg.decision, msg.env.cycle))


def serve(cfg: BusConfig, run: str, scenario: Scenario, store_path: Path) -> None:
    log = setup_logging(PROCESS)
    stop = stop_on_signals()
    entry = GoalEntry(scenario, store_path, engine_validator(scenario), log)
    with open_node(cfg, run, PROCESS) as node:
        entry.node = node
        inbox = node.subscribe(keys.world_state(run))
        for agent in scenario.agent_ids:
            node.subscribe(keys.intention(run, agent), inbox)
            node.serve(keys.goals(run, agent), entry.handle)
        node.declare([keys.stats(run, PROCESS), *(keys.goal_list(run, a)
                                                   for a in scenario.agent_ids)])
        node.announce()
        log.info("serving goals of %s from %s", scenario.agent_ids, store_path)
        while not stop.is_set():
            msg = inbox.get(timeout=0.1)
            if isinstance(msg, WorldState):
                entry.on_world_state(node, msg.env.cycle)
            elif isinstance(msg, Intention):
                entry.on_intention(msg)
    log.info("stopped; %d goals saved in %s", len(entry.store.goals), store_path)


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--scenario", "scenario_file", required=True, type=click.Path(exists=True))
@click.option("--store", "store_file", required=True, type=click.Path(dir_okay=False),
              help="JSON file keeping the goals across restarts.")
@bus_options
def main(run: str, scenario_file: str, store_file: str, bus_config: BusConfig) -> None:
    """The goal-entry process of one run."""
    serve(bus_config, run, load_scenario(scenario_file), Path(store_file))


if __name__ == "__main__":
    main()
