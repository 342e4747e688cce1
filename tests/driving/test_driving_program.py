"""The driving program (programs/driving.tlp) really drives the car: the pure engine decides,
the pymunk world moves, cycle by cycle in one process (tools/commands/simulate.py). Its skills form
a hierarchy (seed 000): an errand reaches the pedals through several levels of skills."""

from __future__ import annotations

from agents.lang import Engine, load_program
from tests.driving.scenarios import PROGRAM, final, goal, scenario
from tools.commands.simulate import simulate
from world.driving.config import load_world_config
from world.driving.perception import perceive
from world.driving.simulation import Simulation


def drive(sc, cycles: int, agent: str = "ME", events: dict | None = None):
    """Run ``sc`` cycle by cycle with the program's engine; yields (cycle, result, world)."""
    world = Simulation(load_world_config(sc.world), sc.run.seed, sc.agent_ids)
    engine = Engine(load_program(PROGRAM))
    state = engine.initial_state()
    for g in sc.goals:
        state = engine.add_goal(state, g.goal, priority=g.priority)
    for cycle in range(cycles):
        if events and cycle in events:
            world.inject(events[cycle])
        result = engine.cycle(state, perceive(world.snapshot(), agent))
        state = result.state
        world.apply_actions(agent, [a.to_list() for a in result.decision.actions])
        yield cycle, result, world
        world.step()


def test_the_laws_are_the_goal_list_and_name_no_car():
    goals = Engine(load_program(PROGRAM)).initial_state().to_dict()["goals"]
    assert [g["goal"] for g in goals] == ["(not-hitting-pedestrians ?self)",
                                         "(at-desired-speed ?self)"]


def test_moves_off_with_the_seed_table_1_skill_and_keeps_its_lane():
    run = simulate(scenario(packages=[{"id": "P1", "address": 10, "street": "B"}],
                            goals=[goal("(package-delivered P1)")]), cycles=150)
    assert run.records[0]["ME"]["actions"] == [["*gas", 6.25]]   # seed 000, Table 1
    car = final(run).car("ME")
    assert 7.0 < car.speed <= 10.0                      # within the Table 2 law, cruising
    assert abs(car.x - 102.0) < 0.5 and car.y > 100.0   # straight up street B, right lane


def test_an_errand_reaches_the_pedals_through_the_skill_hierarchy():
    """Round a right turn at B/SECOND to 6 SECOND: the paths pass through the route, the turn
    and the speed skills, and the car stops at the address."""
    sc = scenario(packages=[{"id": "P1", "address": 6, "street": "SECOND"}],
                  goals=[goal("(package-delivered P1)")])
    paths = set()
    for _, result, world in drive(sc, 600):
        paths.add(tuple(s.skill for s in result.decision.path))
        if world.snapshot().packages[0].delivered:
            break
    assert world.snapshot().packages[0].delivered
    assert ("package-delivered#1", "at-address#1", "address-in-front#1", "took-exit#4",
            "at-turn-speed#2") in paths                 # slowing for the turn, 5 levels down
    assert any(p[3:] == ("took-exit#6",) for p in paths)          # steering the right turn
    assert any(p[1:3] == ("at-address#1", "at-address#2") for p in paths)   # Table 1
    counters = world.snapshot().counters["ME"]
    assert counters["off_road"] == counters["yellow_crossings"] == 0


def test_a_pedestrian_stepping_out_suspends_the_errand_and_brakes():
    """seed 000, 'Adding Goal Priorities': a violated higher goal takes over; the errand waits
    with its path and resumes when the walker is clear."""
    sc = scenario(packages=[{"id": "P1", "address": 10, "street": "B"}],
                  goals=[goal("(package-delivered P1)")])
    walker = {"kind": "pedestrian", "ahead_of": "ME", "dist": 14.0, "lateral": -1.0,
              "speed": 1.4, "id": "WALKER"}             # crossing to the car's left
    statuses, actions = [], []
    for _, result, world in drive(sc, 260, events={120: walker}):
        statuses.append({g.id: g.status.value for g in result.decision.goals})
        actions.append([a.to_list() for a in result.decision.actions])
        snap = world.snapshot()
    assert statuses[119] == {"p1": "satisfied", "p2": "satisfied", "g3": "active"}
    assert statuses[120]["p1"] == "active" and statuses[120]["g3"] == "suspended"
    assert actions[120] == [["*brake", 100]]
    assert snap.counters["ME"]["pedestrian_hits"] == 0
    assert statuses[-1]["g3"] == "active" and snap.car("ME").speed > 3.0   # on its way again


def test_with_no_errand_left_the_car_waits_and_does_nothing():
    sc = scenario(packages=[{"id": "P1", "address": 4, "street": "B"}],
                  goals=[goal("(package-delivered P1)")], pedestrians=8)
    run = simulate(sc, cycles=320)
    assert [p.delivered for p in final(run).packages] == [True]
    done = next(r["cycle"] for r in run.records if r["ME"]["goals"][-1][1] == "satisfied")
    assert all(r["ME"]["actions"] == [] for r in run.records[done:])
    assert final(run).car("ME").speed < 0.5


def test_two_cars_run_one_program_file_each_on_its_own_errand():
    """issue 13: the program binds ?self from each car's own `self` percept."""
    cars = [{"agent": "ME", "street": "B", "from": "FIRST", "toward": "SECOND", "along": 20.0},
            {"agent": "YOU", "street": "SECOND", "from": "C", "toward": "B", "along": 30.0}]
    sc = scenario(packages=[{"id": "P1", "address": 6, "street": "B"},
                            {"id": "P2", "address": 3, "street": "SECOND", "owner": "YOU"}],
                  goals=[goal("(package-delivered P1)"),
                         goal("(package-delivered P2)", agent="YOU")],
                  cars=cars, pedestrians=6, cycles=450)
    assert {str(a.program) for a in sc.agents} == {PROGRAM}
    run = simulate(sc)
    assert {p.id: p.delivered for p in final(run).packages} == {"P1": True, "P2": True}
    for agent in ("ME", "YOU"):
        assert run.records[0][agent]["actions"] == [["*gas", 6.25]]      # each acts itself
        assert final(run).counters[agent]["deliveries"] == 1
        laws = {k: v for k, v in final(run).counters[agent].items() if k != "deliveries"}
        assert sum(laws.values()) == 0, (agent, laws)
