"""The robot's percepts (world/office/percepts.md): neutral lists, pure functions of the
snapshot, and what the robot knows rather than the whole truth."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
from office_helpers import OFFICE, office, percept, percepts, until_done

from world.office.floor import build_floor
from world.office.routes import plan

DOC = Path(__file__).resolve().parents[3] / "world" / "office" / "percepts.md"


def test_percepts_are_neutral_lists_of_symbols_and_numbers():
    for p in percepts(office()):
        assert isinstance(p[0], str) and isinstance(p[1], str) and len(p) % 2 == 0
        assert all(isinstance(v, str | int | float) and not isinstance(v, bool) for v in p)


def test_every_percept_type_is_documented():
    documented = set(re.findall(r'\| `\["([a-z-]+)"', DOC.read_text()))
    world = office(agents=("ME", "R2"))
    world.apply_actions("ME", [["*observe", "r-5306"]])
    for _ in range(5):
        world.step()
    world.apply_actions("ME", [])
    world.inject({"kind": "obstacle", "x": 18.0, "y": 17.0})
    assert {p[0] for p in percepts(world)} <= documented
    assert {"robot", "operation", "room", "distance", "door", "person", "item", "observed",
            "other-robot"} <= {p[0] for p in percepts(world)}


def test_the_robot_percept_at_the_start():
    me = percept(office(), "robot", "ME")
    assert me == {"room": "r-5306", "x": 18.0, "y": 19.5, "heading": 0.0, "speed": 0.0,
                  "moving": "NIL", "carrying": 0, "capacity": 4, "travelled": 0.0}


def test_room_distances_are_the_navigators_routes():
    world = office()
    floor = build_floor(world.config)
    for room in ("r-5301", "r-5313", "r-5318"):
        expected = plan(floor, (18.0, 19.5), room).length
        assert percept(world, "room", room)["dist"] == pytest.approx(expected, abs=1e-3)
    assert percept(world, "room", "r-5306")["dist"] == 0.0
    pairs = percepts(world, kind="distance")
    n = len(floor.rooms)
    assert len(pairs) == n * (n - 1) // 2
    a = {(p[1], p[3]): p[5] for p in pairs}
    assert a[("r-5303", "r-5313")] == pytest.approx(39.0)
    assert percepts(office({"distances": False}), kind="distance") == []


def test_distances_follow_what_the_robot_learns():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    before = percept(world, "room", "r-5313")["dist"]
    world.inject({"kind": "block", "door": "d-south"})
    world.step()
    assert percept(world, "room", "r-5313")["dist"] == before          # not seen yet
    world.apply_actions("ME", [["*goto", "r-5309"]])
    for _ in range(35):
        world.step()
    world.apply_actions("ME", [])
    door = percept(world, "door", "d-south")
    assert (door["kind"], door["corridor"], door["state"]) == ("fire", "c-south", "blocked")
    pairs = {(p[1], p[3]): p[5] for p in percepts(world, kind="distance")}
    assert pairs[("r-5303", "r-5313")] > 39.0 + 20


def test_doors_are_visible_only_within_sight_of_the_robots_space():
    world = office()
    assert percept(world, "door", "d-5306")["visible"] == "T"          # its own, 1.5 m
    assert percept(world, "door", "d-5308")["visible"] == "NIL"        # in c-north, not here
    door = percept(world, "door", "d-5309")
    assert (door["kind"], door["room"], door["state"]) == ("room", "r-5309", "open")


def test_coffee_temperature_is_perceived_only_in_sight():
    world = office({"robots": [{"agent": "ME", "room": "r-5302"}]})
    coffee = percept(world, "item", "coffee-1")
    assert (coffee["holder"], coffee["temp"], coffee["cold"]) == ("r-5302", 75.0, "NIL")
    far = office()
    assert "temp" not in percept(far, "item", "coffee-1")
    assert percept(far, "item", "mail-mitchell")["visible"] == "NIL"


def test_people_where_last_seen_and_other_robots():
    world = office(agents=("ME", "R2"))
    them = percept(world, "other-robot", "R2")
    assert them["room"] == "r-5306" and them["x"] != 18.0               # side by side
    assert percept(world, "person", "jhm") == {"room": "r-5311", "office": "r-5311",
                                               "visible": "NIL", "seen": 0}


def test_a_failed_operation_is_perceived_with_its_code():
    world = office()
    world.apply_actions("ME", [["*deliver", "fax-jhm", "jhm"]])
    op = percept(world, "operation", "ME")
    assert op == {"action": "deliver", "item": "fax-jhm", "to": "jhm", "status": "failed",
                  "reason": "item-not-held", "started": 0, "ended": 0}


def test_perception_of_an_unknown_robot_is_refused():
    from world.errors import WorldError
    with pytest.raises(WorldError, match="no robot 'R9'"):
        OFFICE.perceive(office().snapshot_dict(), "R9")


def test_observation_results_are_remembered():
    world = office({"robots": [{"agent": "ME", "room": "r-5309"}]})
    until_done(world, ["*observe", "r-5309"])
    assert percept(world, "observed", "r-5309")["result"] == "occupied"
