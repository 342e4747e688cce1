"""`teleo simulate`'s agents: world/cycle.py's in-process transport.

Each agent's perception, inference and executive step run one after the other in this
process on the world state the CycleRunner hands over, as the three processes of a launch run
them on it: perception puts the world's static part back into the state's snapshot,
inference reads the world model from the memory the state hands back (what the agent sent
with its last actions, not the engine state it holds), the executive takes its SCS state back
from that memory too, and the actions go back with the memory the agent sends. The user
goals are kept as the goal-entry process keeps them (`Goals`).
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field
from typing import Any

from agents.lang import Engine, EngineState, LangError
from agents.lang.registry import memory_of, remember
from agents.processes.goal_store import GoalStore, GoalStoreError
from agents.processes.goal_sync import GoalSync, validator
from agents.processes.goal_texts import refused_text
from agents.processes.hints import with_hints
from bus.cycle import CycleReport
from tools.records.run_record import GoalHistory
from world.cycle import CycleState
from world.run_scenario import Scenario, ScriptedGoal
from world.static import whole

log = logging.getLogger("tools.commands.simulate")


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


class Goals:
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
    """What one agent saw and did in one cycle, for a recorder
    (tools/records/run_recorders.SimRecorder); ms: compute time per stage [ms]."""

    percepts: list
    outcomes: list
    beliefs: Any
    decision: Any
    ms: dict[str, float]


class InProcessAgents:
    """The agents of `scenario` in this process (world/cycle.py's Agents). `states`: each
    agent's engine state, kept up to date; `run`: the SimRun told each cycle's record and
    goal history; `recorder`: a SimRecorder or None; `static`: the world's static part."""

    def __init__(self, scenario: Scenario, engines: dict[str, Engine],
                 states: dict[str, EngineState], domain: Any, run: SimRun,
                 static: dict[str, Any], recorder: Any = None) -> None:
        self.agents = scenario.agent_ids
        self.engines, self.states, self.domain = engines, states, domain
        self.run, self.static, self.recorder = run, static, recorder
        self.goals = Goals(scenario, engines)

    def act(self, state: CycleState, snap: dict[str, Any]) -> CycleReport:
        t = state.t
        self.goals.before(t, self.states, self.run.history)
        if self.recorder is not None:
            for a in self.agents:
                self.recorder.goal_list(t, a, self.goals.store.goal_list(a))
        seen_snap = whole(self.static, state.snapshot)  # what a perception process puts
        record: dict[str, Any] = {"cycle": t}            # together
        actions, memory, stage_ms = {}, {}, {}
        for a in self.agents:
            memory_in = state.memory.get(a) or {}
            seen = self._agent_cycle(a, seen_snap, state.outcomes.get(a, []), memory_in)
            decision, engine = seen.decision, self.engines[a]
            actions[a] = tuple(act.to_list() for act in decision.actions)
            memory[a] = memory_of(self.states[a], engine.mechanisms)
            stage_ms.update({f"{a}.{k}": v for k, v in seen.ms.items()})
            decided = decision.to_dict()
            self.run.history.feed({"kind": "Intention", "agent": a, "env": {"cycle": t},
                                   "decision": decided})
            self.goals.after(a, with_hints(decided, seen.percepts, engine.program), t)
            record[a] = {"actions": [list(x) for x in actions[a]],
                         "goals": [(g.id, g.status.value) for g in decision.goals],
                         **{s.name: decided[s.name] for s in decision.sections}}
            if self.recorder is not None:   # the memory a launch's messages carry
                self.recorder.agent(t, a, seen, memory_in, memory[a])
        self.run.records.append(record)
        return CycleReport(t, actions, stage_ms=stage_ms, memory=memory)

    def _agent_cycle(self, agent: str, snap: dict[str, Any], outcomes: list,
                     memory: dict[str, Any]) -> AgentCycle:
        """Perception, inference and the executive step of one agent, each timed; the world
        model and the SCS state read from the memory handed back, as the processes read it
        (a malformed one is left out, as they leave it out)."""
        engine, state = self.engines[agent], self.states[agent]
        t0 = time.perf_counter()
        percepts = self.domain.perceive(snap, agent)
        t1 = time.perf_counter()
        try:
            beliefs = engine.infer(percepts, memory.get("model") or ())
        except LangError as exc:
            log.warning("%s: world model dropped: %s", agent, exc)
            beliefs = engine.infer(percepts)
        t2 = time.perf_counter()
        if memory:
            try:
                state = remember(state, memory, engine.program, engine.mechanisms)
            except LangError as exc:
                log.warning("%s: agent memory dropped: %s", agent, exc)
        decision, self.states[agent] = engine.decide(state, percepts, beliefs, outcomes)
        t3 = time.perf_counter()
        ms = {"perception": (t1 - t0) * 1e3, "inference": (t2 - t1) * 1e3,
              "executive": (t3 - t2) * 1e3}
        return AgentCycle(percepts, list(outcomes), beliefs, decision, ms)
