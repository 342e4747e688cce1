"""The driving program (programs/driving.tlp) really drives the car: the pure engine decides,
the pymunk world moves, cycle by cycle in one process (tools/simulate.py)."""

from __future__ import annotations

from agents.lang import Engine, load_program
from tests.driving.scenarios import PROGRAM, scenario
from tools.simulate import simulate
from world.driving.config import load_world_config
from world.driving.perception import perceive
from world.driving.simulation import Simulation
from world.driving.snapshot import WorldSnapshot


def _goal(text: str, at: int = 0, priority: int = 6) -> dict:
    return {"agent": "ME", "goal": text, "priority": priority, "at_cycle": at}


def test_program_loads_with_the_laws_in_priority_order() -> None:
    engine = Engine(load_program(PROGRAM))
    goals = engine.initial_state().to_dict()["goals"]
    texts = [g["goal"] for g in goals]
    assert texts == ["(not-hitting-pedestrians ME)", "(keeping-distance ME)",
                     "(at-desired-speed ME)", "(in-right-lane ME)", "(at-cruising-speed ME)"]


def test_moves_off_with_the_seed_table_1_skill_and_keeps_its_lane() -> None:
    run = simulate(scenario(packages=[{"id": "P1", "address": 10, "street": "B"}]), cycles=150)
    first = run.records[0]["ME"]
    assert ["*gas", 6.25] in first["actions"]          # seed 000, Table 1: stopped -> (*gas 6.25)
    car = WorldSnapshot.from_dict(run.final).car("ME")
    assert 7.0 < car.speed <= 10.0                       # within the Table 2 law, near cruising
    assert abs(car.x - 102.0) < 0.5 and car.y > 100.0    # straight up street B, right lane
    assert run.final["counters"]["ME"]["off_road"] == 0


def test_delivers_a_package_ahead_and_one_round_a_corner() -> None:
    sc = scenario(packages=[{"id": "P1", "address": 6, "street": "B"},
                            {"id": "P2", "address": 6, "street": "THIRD"}],
                  goals=[_goal("(package-delivered P1)"), _goal("(package-delivered P2)", at=150)],
                  pedestrians=8, cycles=600)
    run = simulate(sc)
    counters = run.final["counters"]["ME"]
    assert [p["id"] for p in run.final["packages"] if p["delivered"]] == ["P1", "P2"]
    assert counters["pedestrian_hits"] == 0
    assert counters["off_road"] == counters["yellow_crossings"] == 0
    # no errands left: it waits, stopped
    assert WorldSnapshot.from_dict(run.final).car("ME").speed < 0.5


def test_a_pedestrian_stepping_out_suspends_the_errand_and_brakes() -> None:
    """seed 000, 'Adding Goal Priorities': a violated higher goal takes over. The errand keeps
    only what the law leaves free (the wheel); the pedals are the law's until the walker is
    clear."""
    sc = scenario(packages=[{"id": "P1", "address": 10, "street": "B"}],
                  goals=[_goal("(package-delivered P1)")],
                  events=[{"at_cycle": 120, "kind": "pedestrian", "ahead_of": "ME", "dist": 14.0,
                           "lateral": -1.0, "id": "WALKER"}], cycles=200)
    world = Simulation(load_world_config(sc.world), 7, ["ME"])
    engine = Engine(load_program(PROGRAM))
    state = engine.add_goal(engine.initial_state(), "(package-delivered P1)", priority=6,
                            goal_id="g1")
    statuses = []
    for cycle in range(200):
        if cycle == 120:
            world.inject(sc.events[0].event)
        result = engine.cycle(state, perceive(world.snapshot(), "ME"))
        state = result.state
        world.apply_actions("ME", [a.to_list() for a in result.decision.actions])
        statuses.append({g["id"]: g["status"] for g in result.decision.to_dict()["goals"]})
        if cycle == 121:
            assert ["*brake", 100] in [a.to_list() for a in result.decision.actions]
        world.step()
    assert statuses[119]["p1"] == "satisfied" and statuses[119]["g1"] == "active"
    assert statuses[121]["p1"] == "active"
    assert statuses[121]["p5"] != "active"             # cruising speed gives way: no pedals
    snap = world.snapshot()
    assert snap.counters["ME"]["pedestrian_hits"] == 0
    assert snap.car("ME").speed < 0.5                   # still waiting for the walker
