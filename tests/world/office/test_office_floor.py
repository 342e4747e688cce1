"""The floor of seed 003's example and the navigator's shortest routes over it."""

from __future__ import annotations

import math
from itertools import pairwise

import pytest

from world.errors import ConfigError
from world.office.config import load_office_config
from world.office.floor import build_floor
from world.office.routes import distances_from_node, plan


@pytest.fixture(scope="module")
def floor():
    return build_floor(load_office_config({}))


def test_the_default_floor_has_the_seeds_rooms_and_people(floor):
    kinds = {r.id: r.kind for r in floor.rooms}
    assert kinds["r-5309"] == kinds["r-5311"] == "conference"
    assert {"r-5303", "r-5311", "r-5313"} <= set(kinds) and kinds["r-5313"] == "mailroom"
    config = load_office_config({})
    offices = {p.id: p.room for p in config.people}
    assert offices["mitchell"] == "r-5303" and offices["jhm"] == "r-5311"
    assert len(offices) >= 6
    assert {d.id for d in floor.doors} >= {"d-5309", "d-south", "d-north"}


def test_a_route_is_the_shortest_along_the_corridors(floor):
    # r-5303 (spot at x 11) to r-5313 (x 45): out of the door, 34 m along c-south, in
    route = plan(floor, floor.room("r-5303").spot, "r-5313")
    assert route.length == pytest.approx(1.5 + 1 + 34 + 1 + 1.5)
    assert route.nodes == ("@start", "d-5303", "d-5303/front", "d-5305/front", "d-5307/front",
                           "d-south", "d-5309/front", "d-5311/front", "d-5313/front", "d-5313",
                           "r-5313")
    assert sum(math.dist(a, b) for a, b in pairwise(route.points)) == \
        pytest.approx(route.length)


def test_a_shut_fire_door_sends_the_route_round_the_ring(floor):
    start = floor.room("r-5303").spot
    direct = plan(floor, start, "r-5313")
    around = plan(floor, start, "r-5313", shut=frozenset({"d-south"}))
    assert "d-south" not in around.nodes and {"sw", "nw", "ne", "se"} <= set(around.nodes)
    assert around.length > direct.length + 20


def test_a_shut_room_door_leaves_no_route_into_the_room(floor):
    assert plan(floor, floor.room("r-5303").spot, "r-5309", shut=frozenset({"d-5309"})) is None
    both = frozenset({"d-south", "d-north"})
    assert plan(floor, floor.room("r-5303").spot, "r-5313", shut=both) is None


def test_distances_are_symmetric(floor):
    a = distances_from_node(floor, "r-5302")
    b = distances_from_node(floor, "r-5317")
    assert a["r-5317"] == pytest.approx(b["r-5302"])


def test_a_known_obstacle_blocks_the_corridor_it_lies_in(floor):
    start = floor.room("r-5303").spot
    blocked = plan(floor, start, "r-5313", obstacles=((30.0, 9.0, 0.3),))
    assert "d-south" not in blocked.nodes and "nw" in blocked.nodes


@pytest.mark.parametrize(("table", "message"), [
    ({"hallway": 3}, "unknown keys ['hallway']"),
    ({"speed": 9.0}, "speed: expected float in [0.1, 5]"),
    ({"south": [{"id": "r-1", "door": "ajar"}]}, "door: expected one of"),
    ({"people": [{"id": "ann", "room": "r-9999"}]}, "person ann: unknown room 'r-9999'"),
    ({"items": [{"id": "x", "kind": "mail", "holder": "nobody"}]}, "holder 'nobody'"),
    ({"fire_doors": [{"id": "f", "corridor": "c-south", "at": 11.0}]}, "in front of a room door"),
    ({"robots": [{"agent": "ME", "room": "r-1"}]}, "robot ME: unknown room 'r-1'"),
    ({"people": [{"id": "r-5303", "room": "r-5303"}]}, "ids used twice"),
])
def test_a_bad_world_table_is_refused_naming_the_key(table, message):
    with pytest.raises(ConfigError, match=message.replace("[", r"\[").replace("]", r"\]")):
        build_floor(load_office_config(table))


def test_a_custom_floor_from_the_world_table():
    config = load_office_config({
        "south": ["r-1", {"id": "r-2", "kind": "conference", "width": 10.0}],
        "north": [{"id": "r-3", "kind": "kitchen", "door": "closed"}],
        "fire_doors": [], "people": [{"id": "ann", "room": "r-1"}],
        "items": [{"id": "cup", "kind": "coffee", "holder": "r-3"}]})
    floor = build_floor(config)
    assert floor.width == 16.0 + 2 * 2.0
    assert [r.id for r in floor.rooms] == ["r-1", "r-2", "r-3"]
    assert load_office_config(config.to_dict()) == config
