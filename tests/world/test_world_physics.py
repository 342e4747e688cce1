"""Real pymunk physics in constructed situations: the seed's Table 4 actions move the car."""

from __future__ import annotations

import json

from world.driving.config import CarStart, WorldConfig, load_world_config
from world.driving.perception import perceive
from world.driving.simulation import Simulation
from world.driving.snapshot import WorldSnapshot


def quiet_world(*starts: CarStart, **extra) -> Simulation:
    config = WorldConfig(pedestrians=0, traffic=0, cars=starts, **extra)
    return Simulation(config, seed=1, agents=[s.agent for s in starts])


def drive(sim: Simulation, seconds: float, **actions: list) -> None:
    for agent, acts in actions.items():
        sim.apply_actions(agent, acts)
    for _ in range(round(seconds / sim.config.dt)):
        sim.step()


EAST = CarStart("ME", "FIRST", "A", "B", along=10.0)       # right lane of FIRST, heading east


def test_gas_accelerates_along_the_lane() -> None:
    sim = quiet_world(EAST)
    drive(sim, 4.0, ME=[["*gas", 100]])
    me = sim.snapshot().car("ME")
    assert 9.0 < me.speed < 12.0                       # ~3 m/s^2 less drag
    assert me.x > 10.0 + 15.0 and abs(me.y + 2.0) < 1e-6 and me.heading == 0.0
    assert me.throttle == 100.0 and me.brake == 0.0


def test_drag_settles_the_speed_under_constant_throttle() -> None:
    sim = quiet_world(EAST, ns_streets=tuple("ABCDEFGHI"))   # 800 m east: it stays inside
    drive(sim, 45.0, ME=[["*gas", 30]])
    v1 = sim.snapshot().car("ME").speed
    drive(sim, 5.0)
    v2 = sim.snapshot().car("ME").speed
    assert abs(v2 - v1) < 0.2 and 13.0 < v2 < 14.0   # sqrt((0.9 - 0.05) / 0.0048) = 13.3


def test_brake_stops_the_car() -> None:
    sim = quiet_world(CarStart("ME", "FIRST", "A", "D", along=10.0, speed=15.0))
    drive(sim, 3.0, ME=[["*brake", 100]])
    me = sim.snapshot().car("ME")
    assert me.speed == 0.0 and me.x < 10.0 + 16.0       # v^2 / (2 * 8 m/s^2) ~ 14 m
    assert me.brake == 100.0 and me.throttle == 0.0


def test_steer_left_turns_counter_clockwise_and_right_clockwise() -> None:
    for angle, sign in ((20, 1), (-20, -1)):
        sim = quiet_world(CarStart("ME", "SECOND", "A", "D", along=30.0, speed=5.0))
        drive(sim, 1.0, ME=[["*gas", 10], ["*steer", angle]])
        me = sim.snapshot().car("ME")
        assert sign * me.heading > 10.0 and sign * (me.y - 98.0) > 0.0
        assert me.wheel == angle
    drive(sim, 1.0, ME=[["*straighten"]])
    h = sim.snapshot().car("ME").heading
    drive(sim, 1.0)
    assert sim.snapshot().car("ME").heading == h


def test_a_pedestrian_in_front_is_hit_if_nothing_is_done() -> None:
    sim = quiet_world(CarStart("ME", "FIRST", "A", "D", along=10.0, speed=10.0))
    assert sim.inject({"kind": "pedestrian", "ahead_of": "ME", "dist": 25.0, "id": "M9"}) \
        ["status"] == "done"
    drive(sim, 4.0, ME=[["*cruise"]])
    snap = sim.snapshot()
    assert snap.counters["ME"]["pedestrian_hits"] == 1
    assert {p.id: p.mode for p in snap.pedestrians} == {"M9": "down"}


def test_braking_in_time_spares_the_pedestrian() -> None:
    sim = quiet_world(CarStart("ME", "FIRST", "A", "D", along=10.0, speed=10.0))
    sim.inject({"kind": "pedestrian", "ahead_of": "ME", "dist": 25.0})
    drive(sim, 4.0, ME=[["*brake", 100]])
    snap = sim.snapshot()
    assert snap.counters["ME"]["pedestrian_hits"] == 0 and snap.car("ME").speed == 0.0
    (man,) = [p for p in perceive(snap, "ME") if p[0] == "man"]
    assert man[3] == 0.0 and 10.0 < man[5] < 20.0          # dead ahead, stopped short


def test_a_walker_bumping_a_standing_car_is_no_hit() -> None:
    sim = quiet_world(EAST)
    # beside the car on its right, walking to its left: straight into its flank
    sim.inject({"kind": "pedestrian", "ahead_of": "ME", "dist": 0.0, "lateral": -3.0,
                "speed": 1.4, "heading": 90.0, "id": "M9"})
    drive(sim, 4.0, ME=[["*brake", 100]])
    snap = sim.snapshot()
    assert snap.counters["ME"]["pedestrian_hits"] == 0
    assert {p.id: p.mode for p in snap.pedestrians} != {"M9": "down"}


def test_two_agent_cars_collide() -> None:
    sim = quiet_world(CarStart("ME", "FIRST", "A", "D", along=10.0, speed=10.0),
                      CarStart("YOU", "FIRST", "A", "D", along=40.0))
    drive(sim, 4.0)
    snap = sim.snapshot()
    assert snap.counters["ME"]["vehicle_collisions"] == 1
    assert snap.counters["YOU"]["vehicle_collisions"] == 1
    assert snap.car("ME").speed == 0.0


def test_law_counters_off_road_yellow_line_and_speeding() -> None:
    sim = quiet_world(CarStart("ME", "FIRST", "A", "D", along=10.0, speed=8.0),
                      CarStart("YOU", "SECOND", "A", "D", along=10.0, speed=8.0))
    drive(sim, 1.0, ME=[["*steer", -20]], YOU=[["*steer", 15], ["*gas", 100]])
    drive(sim, 8.0, ME=[["*straighten"]], YOU=[["*straighten"]])
    counters = sim.snapshot().counters
    assert counters["ME"]["off_road"] == 1 and counters["ME"]["speeding_cycles"] == 0
    assert counters["YOU"]["yellow_crossings"] == 1 and counters["YOU"]["speeding_cycles"] > 0


def test_stopping_beside_the_address_delivers_the_package() -> None:
    # FIRST 4 is on the right of an eastbound car; its curb point is at x = 63 m
    packages = [{"id": "P1", "address": 4, "street": "FIRST", "owner": "ME"},
                {"id": "P2", "address": 3, "street": "FIRST", "owner": "ME"}]
    config = load_world_config({"pedestrians": 0, "traffic": 0, "packages": packages,
                                "cars": [{"agent": "ME", "street": "FIRST", "from": "A",
                                          "toward": "B", "along": 40.0, "speed": 5.0}]})
    sim = Simulation(config, 3, ["ME"])
    while sim.snapshot().car("ME").x < 58.0:
        sim.step()
    sim.apply_actions("ME", [["*brake", 100]])
    events = []
    for _ in range(20):
        sim.step()
        events += sim.snapshot().events
    snap = sim.snapshot()
    assert {p.id: p.delivered for p in snap.packages} == {"P1": True, "P2": False}
    assert snap.counters["ME"]["deliveries"] == 1
    assert [(e["kind"], e["package"]) for e in events if e["kind"] == "delivery"] == \
        [("delivery", "P1")]


def test_bad_actions_fail_with_a_reason_and_never_raise() -> None:
    sim = quiet_world(EAST)
    outcomes = sim.apply_actions("ME", [["*gas", 150], ["*brake", -1], ["*steer", 41],
                                        ["*fly"], ["*gas"], ["*gas", True], "junk", [],
                                        ["*cruise", 1], ["*gas", 40]])
    assert [o["status"] for o in outcomes] == ["failed"] * 9 + ["done"]
    assert "out of range" in outcomes[0]["reason"] and "*fly" in outcomes[3]["reason"]
    assert all(o["reason"] for o in outcomes[:9]) and outcomes[9]["reason"] == ""
    assert sim.apply_actions("NOBODY", [["*cruise"]])[0]["status"] == "failed"
    assert sim.apply_actions("ME", "*gas")[0]["status"] == "failed"
    assert sim.snapshot().car("ME").throttle == 40.0


def test_same_seed_same_run_step_for_step() -> None:
    config = WorldConfig(pedestrians=20, traffic=8, crossing_rate=0.2)
    runs = []
    for _ in range(2):
        sim = Simulation(config, seed=42, agents=["ME", "YOU"])
        sim.apply_actions("ME", [["*gas", 40], ["*steer", 3]])
        trace = []
        for _ in range(150):
            sim.step()
            trace.append(sim.snapshot().to_dict())
        runs.append(trace)
    assert runs[0] == runs[1]
    other = Simulation(config, seed=43, agents=["ME", "YOU"])
    other.step()
    assert other.snapshot().to_dict()["pedestrians"] != runs[0][0]["pedestrians"]


def test_snapshot_round_trips_exactly_through_plain_data() -> None:
    sim = Simulation(WorldConfig(pedestrians=5, traffic=3), seed=5, agents=["ME"])
    sim.inject({"kind": "block", "segment": "S7"})
    sim.inject({"kind": "pedestrian", "ahead_of": "ME", "dist": 5.0})
    sim.apply_actions("ME", [["*gas", 50]])
    for _ in range(30):
        sim.step()
    snap = sim.snapshot()
    d = snap.to_dict()
    assert WorldSnapshot.from_dict(json.loads(json.dumps(d))) == snap
    assert WorldSnapshot.from_dict(d).to_dict() == d
    assert snap.cycle == 30 and snap.time == 3.0 and snap.blocked == ("S7",)


def test_traffic_keeps_to_the_road_and_to_the_limit() -> None:
    from world.driving.city import build_city
    config = WorldConfig(pedestrians=10, traffic=10)
    sim, city = Simulation(config, seed=9, agents=[]), build_city(config)
    moved = set()
    for _ in range(400):
        sim.step()
        for c in sim.snapshot().cars:
            assert city.locate(c.x, c.y)[0] != "off" and c.speed <= config.speed_limit
            moved.add((c.id, round(c.x), round(c.y)))
    assert len(moved) > 700


def test_a_malformed_snapshot_dict_is_an_error_naming_the_problem() -> None:
    import pytest

    from world.errors import WorldError
    d = quiet_world(EAST).snapshot().to_dict()
    del d["cars"][0]["speed"]
    with pytest.raises(WorldError, match="speed"):
        WorldSnapshot.from_dict(d)
    with pytest.raises(WorldError, match="cycle"):
        WorldSnapshot.from_dict({"time": 0.0})


def test_a_car_that_drives_off_the_map_stops_at_the_citys_edge() -> None:
    """Issue 31 (N18): a car driven west past street A went on to x = -98.7, off the view's
    map, its percepts still placing it on the street it left. It stops CITY_EDGE past the
    outer streets, where the view still draws it, with one `city_edge` event; its percepts
    say where it is; it can drive back into the city."""
    from world.driving.simulation import CITY_EDGE

    sim = quiet_world(CarStart("ME", "FIRST", "B", "A", along=80.0))   # heading west
    edges = []
    sim.apply_actions("ME", [["*gas", 100]])
    for _ in range(round(30.0 / sim.config.dt)):
        sim.step()
        edges += [e for e in sim.snapshot().events if e["kind"] == "city_edge"]
    me = sim.snapshot().car("ME")
    assert (me.x, me.speed) == (-CITY_EDGE, 0.0)
    assert abs(me.y - 2.0) < 1e-6                                     # in its lane's line
    assert [(e["agent"], e["x"]) for e in edges] == [("ME", -CITY_EDGE)]   # once, not per cycle
    (self_percept,) = [p for p in perceive(sim.snapshot(), "ME") if p[0] == "self"]
    fields = dict(zip(self_percept[2::2], self_percept[3::2], strict=True))
    assert self_percept[1] == "ME" and (fields["x"], fields["street"]) == (-CITY_EDGE, "A")
    drive(sim, 5.0)
    assert sim.snapshot().car("ME").x == -CITY_EDGE                    # it stays there
    drive(sim, 20.0, ME=[["*steer", 40], ["*gas", 100]])     # turns, slowly, and drives away
    me = sim.snapshot().car("ME")
    assert me.x > -CITY_EDGE and me.speed > 5.0
