"""Simulator-driven traffic and pedestrians, and events injected while the world runs."""

from __future__ import annotations

import math

from world.driving.config import CarStart, WorldConfig
from world.driving.perception import perceive
from world.driving.simulation import Simulation


def test_traffic_stops_for_a_pedestrian_in_its_lane() -> None:
    sim = Simulation(WorldConfig(pedestrians=0, traffic=1), seed=2, agents=[])
    t = sim.traffic[0]
    while sim.paths[t.key].length - t.s < 40.0 or t.key[0] != "lane":
        sim.step()
    h = math.radians(t.heading)
    px, py = t.x + 25.0 * math.cos(h), t.y + 25.0 * math.sin(h)
    assert sim.inject({"kind": "pedestrian", "x": px, "y": py, "id": "M1"})["status"] == "done"
    for _ in range(50):
        sim.step()
    car = sim.snapshot().car("V1")
    assert car.speed == 0.0 and 2.0 < math.hypot(car.x - px, car.y - py) < 25.0


def test_traffic_yields_to_a_car_inside_the_intersection() -> None:
    # an agent car parked in the middle of intersection I6 (B x SECOND) blocks everyone
    config = WorldConfig(pedestrians=0, traffic=6,
                         cars=(CarStart("ME", "SECOND", "A", "B", along=100.0),))
    sim = Simulation(config, seed=4, agents=["ME"])
    for _ in range(600):
        sim.step()
    snap = sim.snapshot()
    assert snap.counters["ME"]["vehicle_collisions"] == 0
    waiting = [c for c in snap.cars if c.kind == "traffic" and c.speed == 0.0
               and math.hypot(c.x - 100.0, c.y - 100.0) < 30.0]
    assert waiting


def test_pedestrians_walk_the_sidewalks_and_cross_the_road() -> None:
    from world.driving.city import build_city
    config = WorldConfig(pedestrians=30, traffic=0, crossing_rate=0.5)
    sim, city = Simulation(config, seed=8, agents=[]), build_city(config)
    modes = set()
    for _ in range(200):
        sim.step()
        for p in sim.snapshot().pedestrians:
            modes.add(p.mode)
            kind, _, _, _ = city.locate(p.x, p.y)
            crosswalk = min(math.hypot(p.x - n.x, p.y - n.y) for n in city.intersections) < 11
            if p.mode == "walk" and kind == "segment" and not crosswalk:
                raise AssertionError(f"{p.id} walks on the road at {p.x:.1f}, {p.y:.1f}")
    assert {"walk", "cross"} <= modes


def test_injected_events_block_roads_add_packages_and_fail_softly() -> None:
    sim = Simulation(WorldConfig(pedestrians=0, traffic=0), seed=1, agents=["ME"])
    assert sim.inject({"kind": "block", "segment": "S2"})["status"] == "done"
    assert sim.inject({"kind": "package", "id": "P9", "address": 2, "street": "B",
                       "owner": "ME"})["status"] == "done"
    bad = [sim.inject(e) for e in ({"kind": "block", "segment": "S999"}, {"kind": "meteor"},
                                   {"kind": "package", "id": "P9", "address": 2,
                                    "street": "B", "owner": "ME"},
                                   {"kind": "pedestrian", "ahead_of": "NOBODY", "dist": 3},
                                   "junk")]
    assert [o["status"] for o in bad] == ["failed"] * 5
    assert all(o["reason"].startswith("inject:") for o in bad)
    sim.step()
    snap = sim.snapshot()
    assert snap.blocked == ("S2",)
    assert [e["kind"] for e in snap.events] == ["injected", "injected"]
    assert any(p[:2] == ["package", "P9"] for p in perceive(snap, "ME"))


def test_several_agent_cars_drive_independently() -> None:
    sim = Simulation(WorldConfig(pedestrians=0, traffic=0), seed=1, agents=["A1", "A2", "A3"])
    sim.apply_actions("A1", [["*gas", 50]])
    sim.apply_actions("A3", [["*gas", 20], ["*steer", 10]])
    for _ in range(20):
        sim.step()
    snap = sim.snapshot()
    speeds = {a: snap.car(a).speed for a in ("A1", "A2", "A3")}
    assert speeds["A1"] > speeds["A3"] > speeds["A2"] == 0.0
    assert set(snap.counters) == {"A1", "A2", "A3"}
    assert len({(snap.car(a).x, snap.car(a).y) for a in speeds}) == 3
    assert all(perceive(snap, a)[0][0] == "street" for a in speeds)


def test_dense_traffic_keeps_flowing() -> None:
    sim = Simulation(WorldConfig(pedestrians=10, traffic=16), seed=6, agents=[])
    travelled = dict.fromkeys((t.id for t in sim.traffic), 0.0)
    for _ in range(600):
        before = {t.id: (t.x, t.y) for t in sim.traffic}
        sim.step()
        for t in sim.traffic:
            travelled[t.id] += math.hypot(t.x - before[t.id][0], t.y - before[t.id][1])
    assert min(travelled.values()) > 150.0      # of at most 900 m in 60 s


def test_events_a_simulation_cannot_carry_are_refused_with_the_reason() -> None:
    """Issue 12, item 2: a pedestrian at 1e308 m/s, a package named by a control character,
    an owner that is no agent: each refused, naming the field and what would be right."""
    sim = Simulation(WorldConfig(pedestrians=0, traffic=0), seed=1, agents=["ME"])
    cases = {
        "speed: expected a number in [0, 10], got 1e+308":
            {"kind": "pedestrian", "ahead_of": "ME", "dist": 20, "speed": 1e308},
        "dist: expected a number in [-500, 500], got 1e+300":
            {"kind": "pedestrian", "ahead_of": "ME", "dist": 1e300},
        "x: expected a number in [-100, 400], got -5000":
            {"kind": "pedestrian", "x": -5000, "y": 10},
        "id: expected a name of letters, digits": {"kind": "package", "id": "\u0000",
                                                   "address": 2, "street": "B", "owner": "ME"},
        "owner: expected one of the agents ['ME'], got 'NOBODY'":
            {"kind": "package", "id": "P7", "address": 2, "street": "B", "owner": "NOBODY"},
        "ahead_of: unknown agent 'YOU'; agents: ['ME']":
            {"kind": "pedestrian", "ahead_of": "YOU", "dist": 20},
    }
    for reason, event in cases.items():
        outcome = sim.inject(event)
        assert outcome["status"] == "failed" and reason in outcome["reason"], outcome
    sim.step()
    snap = sim.snapshot()
    assert snap.pedestrians == () and [p.id for p in snap.packages] == []
    assert sim.inject({"kind": "pedestrian", "ahead_of": "ME", "dist": 20,
                       "speed": 1.5})["status"] == "done"
