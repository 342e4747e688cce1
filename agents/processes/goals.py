"""The goal-entry process: users' goal requests in, one goal list per agent per cycle out.

    python -m agents.processes.goals --run RUN --scenario FILE --store FILE [bus flags]

It answers GoalRequests (post, cancel, priority, list) on teleo/<run>/agent/<agent>/goals at
any time, validating a post against the agent's program (Engine.add_goal: an unknown concept
or a wrong arity is refused with the engine's reason). When it sees the world state of cycle
t it applies the scenario's scripted requests of cycle t and publishes each agent's goal list
of t, the executive's goal input (a request received while running takes effect at the next
cycle it publishes). It reads the executives' intentions to keep each goal's status
(ROGUE, seed 003: asynchronous requests with priorities).

Requests are bounded (docs/bus.md, "Goal requests"): each client (the request envelope's
sender) and all clients together are rate-limited (request_limits.py), and the store bounds a
goal's length, the priority range and the live goals per agent (goal_store.py). A request
that changes the store is saved durably before it is answered, so an acknowledged goal
survives any crash; the statuses mirrored from intentions are saved at most every
SAVE_PERIOD, and at the end (before the session closes, with the intentions still queued).
A damaged store file is recovered on start (goal_file.py).
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from typing import Any

import click

from agents.lang.core.limits import shorten
from agents.processes import goal_file
from agents.processes.common import setup_logging, stop_on_signals
from agents.processes.goal_store import MAX_ID_CHARS, GoalStore, GoalStoreError
from agents.processes.goal_texts import program_goal_problem, rank_problem, refused_text
from agents.processes.goal_warnings import Warner, engine_warner
from agents.processes.request_limits import RequestLimiter
from agents.processes.swapping import ProgramWatch
from bus import keys
from bus.config import BusConfig, bus_options
from bus.messages import GoalList, GoalReply, GoalRequest, Intention, ProcessStats, WorldState
from bus.node import Node, open_node
from bus.stage import QUIET_S
from world.run_scenario import Scenario, ScriptedGoal, load_scenario

PROCESS = "goals"
SAVE_PERIOD = 1.0  # [s] between saves of statuses mirrored from the executives' intentions


def engine_validator(scenario: Scenario):
    """validate(agent, goal, priority) -> "" or the engine's reason, one Engine per agent."""
    return ProgramWatch(scenario).validate


def standing_goals(scenario: Scenario) -> dict[str, tuple[str, ...]]:
    """Each agent's program goals (p1..pn) as text, in order: what a user goal may not rank
    above unless forced (goal_texts.rank_problem)."""
    return ProgramWatch(scenario).standing


class GoalEntry:
    """The process's state: the store, its file, the limiter, the last goal lists published."""

    def __init__(self, scenario: Scenario, store_path: Path, validate, log,
                 clock=time.monotonic, standing: dict[str, tuple[str, ...]] | None = None,
                 warn: Warner | None = None) -> None:
        self.scenario = scenario
        self.standing = standing or {}  # agent -> its program goals (the priority rule)
        self.path = store_path
        self.validate = validate
        self.warn = warn  # (agent, goal) -> "" or a warning for the reply (goal_warnings.py)
        self.log = log
        self.clock = clock  # [s], monotonic: for the rate limits and the status saves
        opened = goal_file.open_store(store_path)
        if opened.incident:
            log.error("%s", opened.incident)
        self.store = opened.store
        self.limiter = RequestLimiter()
        self.lock = threading.Lock()  # the query handler runs on zenoh's thread
        self.cycle = -1
        self.published: dict[str, tuple[dict[str, Any], ...]] = {}
        self.node: Node | None = None  # set once the session is open
        self.unsaved = False  # statuses mirrored but not yet saved
        self._deferred = False  # scripted requests being applied: saved once after them
        self.saved_at = clock()

    def _commit(self, store: GoalStore) -> None:
        """Make `store` current and save it before anyone is told; while `_deferred`, only
        make it current."""
        if self._deferred:
            self.store, self.unsaved = store, True
            return
        if store == self.store and not self.unsaved:
            return
        try:
            goal_file.save(store, self.path)
        except OSError as exc:
            raise GoalStoreError(f"not done: the goal store {self.path} cannot be saved "
                                 f"({exc})") from None
        self.store, self.unsaved, self.saved_at = store, False, self.clock()

    def flush(self, force: bool = False) -> None:
        """Save mirrored statuses if SAVE_PERIOD has passed since the last save (or `force`)."""
        if not self.unsaved:
            return
        with self.lock:
            if not self.unsaved or not (force or self.clock() - self.saved_at >= SAVE_PERIOD):
                return
            try:
                self._commit(self.store)
            except GoalStoreError as exc:
                self.log.error("%s", exc)
                self.saved_at = self.clock()  # retry after another period

    def handle(self, request: GoalRequest) -> GoalReply:
        """Answer one request (called on zenoh's callback thread)."""
        ok, reason, goals, cycle = self.answer(request)
        return GoalReply(self.node.envelope(cycle), ok, reason, goals)

    def answer(self, request: GoalRequest) -> tuple[bool, str, tuple[dict[str, Any], ...], int]:
        """(ok, reason, the agent's goals, cycle) for one request; refusals say why."""
        with self.lock:
            try:
                refusal = self.limiter.admit(request.env.sender, self.clock())
                if refusal:
                    raise GoalStoreError(refusal)
                reason = self._apply(request.op, request.agent, request.goal, request.priority,
                                     request.goal_id, self.cycle + 1, request.force,
                                     (request.once, request.deadline))
                ok = True
            except GoalStoreError as exc:
                reason, ok = str(exc), False
            goals = tuple(g.to_dict() for g in self.store.for_agent(request.agent))
            cycle = self.cycle
        self.log.info("%s %s %s -> %s", shorten(request.op), shorten(request.agent),
                      shorten(request.goal or request.goal_id), reason)
        return ok, reason, goals, cycle

    def _apply(self, op: str, agent: str, goal: str, priority: int, goal_id: str,
               at: int, force: bool = False, ends: tuple[bool, int] = (False, 0)) -> str:
        """Apply one request taking effect at cycle `at`; returns what was done. A post or a
        priority that ranks a goal above the program's standing goals is refused unless
        `force` (then the reply says what it outranks)."""
        if agent not in self.scenario.agent_ids:
            raise GoalStoreError(f"no agent {shorten(agent)!r} in this run "
                                 f"(agents: {', '.join(self.scenario.agent_ids)})")
        if len(goal_id) > MAX_ID_CHARS:
            raise GoalStoreError(f"goal id {shorten(goal_id)!r}: longer than {MAX_ID_CHARS} "
                                 "characters")
        if op == "post":
            forced = self._rank(agent, priority, force)
            store, record = self.store.post(agent, goal, priority, at, self.validate, *ends)
            self._commit(store)
            warning = self.warn(agent, record.goal) if self.warn is not None else ""
            how = "; once" * record.once + (f"; deadline {record.deadline} cycles"
                                            if record.deadline else "")
            return (f"posted {record.id} for {agent}: {record.goal} (from cycle {at}){how}{forced}"
                    + (f"; warning: {warning}" if warning else ""))
        if op in ("cancel", "priority"):
            self._not_a_program_goal(agent, goal_id, op)
        if op == "cancel":
            self._commit(self.store.cancel(goal_id, at, force))
            return f"cancelled {goal_id} (from cycle {at})"
        if op == "priority":
            forced = self._rank(self.store.get(goal_id).agent, priority, force)
            self._commit(self.store.set_priority(goal_id, priority, at))
            return f"{goal_id} now has priority {priority} (from cycle {at}){forced}"
        if op == "list":
            return ""
        raise GoalStoreError(f"unknown op {shorten(op)!r}: expected post, cancel, priority or "
                             "list")

    def _not_a_program_goal(self, agent: str, goal_id: str, op: str) -> None:
        """Refuse to cancel or reprioritise a program goal (goal_texts.program_goal_problem)."""
        problem = program_goal_problem(self.standing.get(agent, ()), agent, goal_id, op)
        if problem:
            raise GoalStoreError(problem)

    def _rank(self, agent: str, priority: int, force: bool) -> str:
        """The priority rule: raises GoalStoreError when `priority` ranks a goal above the
        agent's program goals and not `force`; returns the note for a forced one."""
        problem = rank_problem(self.standing.get(agent, ()), priority)
        if problem and not force:
            raise GoalStoreError(f"{problem} (teleo goal ... --force)")
        return f"; forced: {problem.split(': the agent')[0]}" if problem else ""

    def on_world_state(self, node: Node, cycle: int) -> ProcessStats:
        """Apply the scripted requests due, then publish every agent's goal list of `cycle`
        with this process's stats (bus/stats.py; the executive's Actions carry them on);
        returns the stats, which `serve` sends alone once idle. A repeated cycle (re-sent
        after a restart) gets the same lists again."""
        t0 = time.perf_counter()
        with self.lock:
            if cycle != self.cycle:
                self.cycle = cycle
                self._scripted(cycle)
                self.published = {a: self.store.goal_list(a) for a in self.scenario.agent_ids}
            lists = dict(self.published)
        env = node.envelope(cycle)
        ms = (time.perf_counter() - t0) * 1e3
        carried = {PROCESS: [ms, 0]}
        node.publish_many([(keys.goal_list(node.run, agent), GoalList(env, agent, goals, carried))
                           for agent, goals in lists.items()])
        return ProcessStats(env, PROCESS, ms, 0)

    def _scripted(self, cycle: int) -> None:
        """Apply the scenario's requests due at `cycle`, then save the store once, before the
        cycle's goal lists (nobody waits for their answers; a failed save: flush retries)."""
        due = [i for i, g in enumerate(self.scenario.goals)
               if g.at_cycle <= cycle and i not in self.store.scripted_done]
        if not due:
            return
        self._deferred = True
        try:
            for i in due:
                self._run_scripted(self.scenario.goals[i])
        finally:
            self._deferred = False
        marked = self.store.mark_scripted(due)   # a new store: always saved
        try:
            self._commit(marked)
        except GoalStoreError as exc:   # kept, done once, and saved by a later flush
            self.store, self.unsaved = marked, True
            self.log.error("scripted requests %s: %s", due, exc)

    def _run_scripted(self, g: ScriptedGoal) -> None:
        try:
            reason = self._apply(g.op, g.agent, g.goal, g.priority, g.goal_id, self.cycle,
                                 g.force, (g.once, g.deadline))
            self.log.info("scripted request at cycle %d: %s", self.cycle, reason)
        except GoalStoreError as exc:
            self.log.warning("scripted request refused: %s", exc)
            self.store = self.store.refusing(refused_text(g.op, g.goal_id, g.goal, self.cycle, exc))

    def on_intention(self, msg: Intention) -> None:
        """Mirror the statuses the executive reported; saved later (flush), not every cycle.
        An intention whose decision does not fit (goal_store.DECISION) is logged and left."""
        with self.lock:
            try:
                store = self.store.update_from_intention(msg.agent, msg.decision,
                                                         msg.env.cycle)
            except GoalStoreError as exc:
                self.log.warning("refused: %s", exc)
                return
            if store is not self.store:
                self.store, self.unsaved = store, True


def serve(cfg: BusConfig, run: str, scenario: Scenario, store_path: Path) -> None:
    log = setup_logging(PROCESS)
    stop = stop_on_signals()
    programs = ProgramWatch(scenario)   # swapped programs too (agents/processes/swapping.py)
    loaded = {agent: engine.program for agent, engine in programs.engines.items()}
    entry = GoalEntry(scenario, store_path, programs.validate, log, standing=programs.standing,
                      warn=engine_warner(scenario, loaded, eager=True))
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
        # the last cycle's stats, sent alone once idle QUIET_S after it (as bus/stage.py)
        quiet: ProcessStats | None = None
        quiet_at = 0.0
        while not stop.is_set():
            wait = 0.1 if quiet is None else max(0.0, min(0.1, quiet_at - time.monotonic()))
            msg = inbox.get(timeout=wait)
            if isinstance(msg, WorldState):
                programs.follow(msg.control, log)
                quiet = entry.on_world_state(node, msg.env.cycle)
                quiet_at = time.monotonic() + QUIET_S
            elif isinstance(msg, Intention):
                entry.on_intention(msg)
            if quiet is not None and time.monotonic() >= quiet_at:
                node.publish(keys.stats(run, PROCESS), quiet)
                quiet = None
            entry.flush()
        while (msg := inbox.get(timeout=0)) is not None:   # saved before the session
            if isinstance(msg, Intention):                  # closes: a close can be slow,
                entry.on_intention(msg)                     # and a slow stopper is killed
        entry.flush(force=True)
        log.info("stopped; %d goals saved in %s", len(entry.store.goals), store_path)


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--scenario", "scenario_file", required=True, type=click.Path(exists=True))
@click.option("--store", "store_file", required=True, type=click.Path(dir_okay=False),
              help="JSON file keeping the goals across restarts.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="A field of the scenario changed for this run (world/overrides.py).")
@bus_options
def main(run: str, scenario_file: str, store_file: str, overrides: tuple[str, ...],
         bus_config: BusConfig) -> None:
    """The goal-entry process of one run."""
    serve(bus_config, run, load_scenario(scenario_file, overrides), Path(store_file))


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
