"""The cycle core (world/cycle.py) over the real driving world, with a transport written here
that answers as agents would: the order of a cycle, the memory round trip, the safe action of
an agent given the no-op, the scripted events at their cycle; and `teleo simulate`'s
in-process agents read the world model from the memory handed back, not from their engine."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

from agents.lang import Engine, load_program
from bus.cycle import CycleReport
from tools.commands.scenario_check import load_checked
from tools.commands.sim_agents import InProcessAgents, SimRun
from world.cycle import CycleRunner, CycleState
from world.domain import get_domain
from world.driving.config import CarStart, WorldConfig
from world.driving.simulation import Simulation
from world.scenario_types import ScriptedEvent
from world.trace import trace_line

ROOT = Path(__file__).resolve().parents[2]
CARS = (CarStart("ME", "FIRST", "A", "D", along=10.0, speed=10.0),
        CarStart("YOU", "FIRST", "A", "D", along=40.0))
PEDESTRIAN = {"kind": "pedestrian", "ahead_of": "ME", "dist": 30.0}


@dataclass
class Scripted:
    """Agents that send `gas` and, as memory, the cycle they acted at; YOU is given the no-op
    at cycle 1 (its actions did not come). Keeps every state it was handed."""

    seen: list[CycleState] = field(default_factory=list)

    def act(self, state: CycleState, snap: dict) -> CycleReport:
        self.seen.append(state)
        t = state.t
        noop = ("YOU",) if t == 1 else ()
        return CycleReport(t, {"ME": (["*gas", 40],), "YOU": () if noop else (["*gas", 20],)},
                           noop=noop,
                           memory={"ME": {"acted": t // 2},
                                   **({} if noop else {"YOU": {"acted": t}})})


def world() -> Simulation:
    return Simulation(WorldConfig(pedestrians=0, traffic=0, cars=CARS), 1, ["ME", "YOU"])


def test_a_cycle_hands_back_outcomes_and_memory_and_stops_an_agent_given_the_no_op() -> None:
    runner = CycleRunner(world(), ["ME", "YOU"], [ScriptedEvent(2, PEDESTRIAN)])
    agents = Scripted()
    done = [runner.cycle(t, agents) for t in range(4)]
    first, second, third = agents.seen[:3]
    assert first.memory == {"ME": {}, "YOU": {}} and first.outcomes == {"ME": [], "YOU": []}
    assert second.memory == {"ME": {"acted": 0}, "YOU": {"acted": 0}}   # sent at 0, back at 1
    assert third.memory["YOU"] == {"acted": 0}   # the no-op sends none: the last one is kept
    assert second.outcomes["ME"] and second.outcomes["ME"][0]["status"] == "done"
    assert done[1].applied["YOU"] == [["*brake", 100]]   # the world's safe action
    assert done[0].applied == {"ME": [["*gas", 40]], "YOU": [["*gas", 20]]}
    assert [d.changed for d in done] == [
        {"ME": {"acted": 0}, "YOU": {"acted": 0}}, {}, {"ME": {"acted": 1}, "YOU": {"acted": 2}},
        {"YOU": {"acted": 3}}]
    assert [len(s.events) for s in agents.seen] == [0, 0, 1, 0]   # scripted at cycle 2
    assert third.events[0]["event"] == PEDESTRIAN
    assert "config" not in first.snapshot and runner.static   # the static part told apart
    assert done[2].trace() == trace_line(2, done[2].snap, done[2].applied, done[2].injected,
                                         done[2].changed)
    assert done[1].snap["cycle"] == 1 and done[3].snap["cycle"] == 3


def test_two_runners_of_one_world_and_agents_give_the_same_trace() -> None:
    lines = []
    for _ in range(2):
        runner, agents = CycleRunner(world(), ["ME", "YOU"], [ScriptedEvent(1, PEDESTRIAN)]), \
            Scripted()
        lines.append("".join(runner.cycle(t, agents).trace() for t in range(6)))
    assert lines[0] == lines[1] and lines[0].count("\n") == 6


class Kept:
    """A simulate recorder that keeps what each agent saw (tools/commands/sim_agents.py)."""

    def __init__(self) -> None:
        self.seen: list = []

    def goal_list(self, *_told) -> None:
        pass

    def agent(self, t: int, agent: str, seen, memory_in: dict, memory_out: dict) -> None:
        self.seen.append((seen, memory_in, memory_out))


def errands_beliefs(memory: dict) -> tuple[set, dict]:
    """The beliefs ME infers at cycle 0 of the errands demo, in process, handed `memory`
    (fresh engines: whatever the model holds comes from the memory), and the memory it
    sends back."""
    scenario, _ = load_checked(ROOT / "scenarios" / "errands_demo.toml")
    domain = get_domain(scenario.domain)
    sim = domain.create(scenario.world_table, scenario.run.seed, scenario.agent_ids)
    engines = {a.id: Engine(load_program(a.program), solver=a.impasse_handler)
               for a in scenario.agents}
    runner = CycleRunner(sim, scenario.agent_ids, scenario.events)
    kept = Kept()
    team = InProcessAgents(scenario, engines, {a: e.initial_state() for a, e in engines.items()},
                           domain, SimRun(), runner.static, kept)

    class Handing:
        def act(self, state: CycleState, snap: dict) -> CycleReport:
            return team.act(replace(state, memory=memory), snap)

    report = runner.cycle(0, Handing()).report
    return {tuple(b.to_list()) for b in kept.seen[0][0].beliefs}, report.memory["ME"]


def test_simulate_infers_from_the_memory_handed_back_not_from_its_engine() -> None:
    """As a launch's inference process, whose engine holds no world model: a fact in the
    model the state hands back is believed; none is believed without it."""
    told, sent = errands_beliefs({"ME": {"model": [["on-route", "ME"]]}})
    alone, _ = errands_beliefs({})
    assert told - alone == {("on-route", "ME")} and not alone - told
    assert "scs" in sent   # what the executive sends back: the SCS threads it runs
