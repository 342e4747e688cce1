"""Events and faults injected into the office world (`teleo event`, scripted [[events]]):
each kind does what it says, and a bad one is refused with the reason, changing nothing."""

from __future__ import annotations

import json

import pytest
from office_helpers import events, office, percept, percepts, until_done

from world.office import EVENT_KINDS


def test_doors_close_block_and_open():
    world = office()
    for kind, state in (("close", "closed"), ("block", "blocked"), ("open", "open")):
        assert world.inject({"kind": kind, "door": "d-5303"}) == {
            "event": {"kind": kind, "door": "d-5303"}, "status": "done", "reason": ""}
        assert world.snapshot_dict()["doors"]["d-5303"] == state
    world.inject({"kind": "close", "door": "d-5303"})
    world.step()
    assert world.snapshot_dict()["events"] == [
        {"kind": "injected", "cycle": 0, "event": {"kind": kind, "door": "d-5303"}}
        for kind in ("close", "block", "open", "close")]


def test_a_person_moves_with_what_they_hold():
    world = office({"robots": [{"agent": "ME", "room": "r-5310"}]})
    world.inject({"kind": "move", "person": "jhm", "room": "r-5310"})
    world.step()
    jhm = percept(world, "person", "jhm")
    assert (jhm["room"], jhm["office"], jhm["visible"]) == ("r-5310", "r-5311", "T")
    _, out = until_done(world, ["*acquire", "fax-jhm", "jhm"])
    assert out["status"] == "done"


def test_the_robot_learns_only_what_it_sees():
    world = office()
    world.inject({"kind": "move", "person": "mitchell", "room": "r-5310"})
    world.inject({"kind": "close", "door": "d-5317"})
    world.step()
    assert percept(world, "person", "mitchell")["room"] == "r-5303"   # not seen leaving
    assert percept(world, "door", "d-5317")["state"] == "open"        # not seen shut
    assert percept(world, "room", "r-5317")["reachable"] == "T"
    until_done(world, ["*goto", "r-5303"])
    assert percept(world, "person", "mitchell")["room"] == "unknown"


def test_a_new_item_and_a_meeting():
    world = office()
    assert world.inject({"kind": "item", "item": "fax-9", "type": "fax", "holder": "reid",
                         "to": "jhm"})["status"] == "done"
    fax = percept(world, "item", "fax-9")
    assert (fax["kind"], fax["holder"], fax["to"]) == ("fax", "reid", "jhm")
    world.inject({"kind": "item", "item": "latte", "type": "coffee", "holder": "r-5310"})
    assert world.snapshot_dict()["items"][-1]["temperature"] == 75.0
    world.inject({"kind": "occupants", "room": "r-5316", "count": 3})
    assert world.snapshot_dict()["occupants"]["r-5316"] == 3


def test_someone_else_can_hand_an_item_over():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    assert world.inject({"kind": "give", "item": "mail-mitchell", "to": "r-5313"})["status"] == \
        "done"
    assert percept(world, "item", "mail-mitchell")["holder"] == "r-5313"
    world.inject({"kind": "give", "item": "fax-jhm", "to": "mitchell"})
    until_done(world, ["*acquire", "fax-jhm", "mitchell"])
    out = world.inject({"kind": "give", "item": "fax-jhm", "to": "jhm"})
    assert out["status"] == "failed" and "carried by robot ME" in out["reason"]


def test_obstacles_come_and_go():
    world = office()
    assert world.inject({"kind": "obstacle", "x": 30.0, "y": 17.0})["status"] == "done"
    assert world.inject({"kind": "obstacle", "x": 40.0, "y": 9.0, "id": "box"})["status"] == \
        "done"
    assert [o["id"] for o in world.snapshot_dict()["obstacles"]] == ["box", "o1"]
    assert world.inject({"kind": "clear", "obstacle": "o1"})["status"] == "done"
    assert [o["id"] for o in world.snapshot_dict()["obstacles"]] == ["box"]


def test_a_robot_forgets_an_obstacle_it_sees_gone():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    world.inject({"kind": "obstacle", "x": 20.0, "y": 9.0, "id": "cart"})
    _, out = until_done(world, ["*goto", "r-5313"])
    assert "bumped" in out["reason"] and percept(world, "obstacle", "cart")["x"] == 20.0
    world.inject({"kind": "clear", "obstacle": "cart"})
    world.step()
    assert percepts(world, kind="obstacle") == []                 # it stands within sight
    assert [e["obstacle"] for e in events(world, "obstacle-gone")] == ["cart"]


@pytest.mark.parametrize(("event", "reason"), [
    ({"kind": "close", "door": "d-9"}, "door: expected a door id, one of ["),
    ({"kind": "close", "door": "d-5306"}, "robot ME stands in the doorway of d-5306"),
    ({"kind": "move", "person": "mitchell", "room": "moon"}, "room: expected a room"),
    ({"kind": "move", "person": "santa", "room": "r-5303"}, "person: expected a person"),
    ({"kind": "false-success", "agent": "ME", "mode": "lost"}, "mode: expected one of"),
    ({"kind": "false-success", "agent": "R2"}, "agent: expected a robot's agent id"),
    ({"kind": "cool", "item": "mail-reid"}, "item: expected a coffee item"),
    ({"kind": "cool", "item": "coffee-1", "temperature": 90}, "temperature: expected a number "
                                                              "in [-20, 75]"),
    ({"kind": "item", "item": "fax-jhm", "type": "fax", "holder": "jhm"}, "expected a new id"),
    ({"kind": "item", "item": "x", "holder": "jhm"}, "type: missing; expected the item's kind"),
    ({"kind": "item", "item": "x", "type": "fax", "holder": "ME"}, "holder: expected a person"),
    ({"kind": "give", "item": "mail-9", "to": "jhm"}, "item: expected an item id"),
    ({"kind": "give", "item": "fax-jhm", "to": "ME"}, "to: expected a person or room"),
    ({"kind": "occupants", "room": "r-5309", "count": -1}, "count: expected an integer"),
    ({"kind": "occupants", "room": "r-5309", "count": 2.5}, "count: expected an integer"),
    ({"kind": "obstacle", "x": 20.0, "y": 13.0}, "is inside a wall"),
    ({"kind": "obstacle", "x": 18.0, "y": 19.5}, "is under robot ME"),
    ({"kind": "obstacle", "y": 9.0}, "x: missing; expected a finite number"),
    ({"kind": "move", "person": "jhm", "room": "r-5309", "colour": "red"},
     "unknown field 'colour'; known: kind, person, room"),
    ({"kind": "move", "person": [], "room": "r-5309"}, "person: expected a person, got []"),
    ({"kind": "clear", "obstacle": "o7"}, "obstacle: expected an obstacle id"),
    ({"kind": "stall", "agent": "ME", "seconds": "long"}, "seconds: expected a number"),
    ({"kind": "teleport"}, "unknown kind 'teleport'; known: open close block"),
])
def test_a_bad_event_is_refused_with_the_reason_and_changes_nothing(event, reason):
    world = office()
    if event.get("door") == "d-5306":                    # first drive into the lab's doorway
        world.apply_actions("ME", [["*goto", "r-5302"]])
        for _ in range(3):
            world.step()
    before = json.dumps(world.snapshot_dict(), sort_keys=True)
    out = world.inject(event)
    assert out["status"] == "failed" and reason in out["reason"], out
    assert out["reason"].startswith(f"inject {event['kind']!r}: ")
    assert json.dumps(world.snapshot_dict(), sort_keys=True) == before


def test_not_a_dict_is_refused():
    assert office().inject(["close"])["reason"].startswith('inject: expected a map with a "kind"')


def test_every_event_kind_is_listed_for_scenario_checks():
    assert set(EVENT_KINDS) == {"open", "close", "block", "move", "false-success", "cool",
                                "item", "give", "occupants", "obstacle", "clear", "stall"}


def test_people_wander_from_their_offices_and_come_back():
    world = office({"wander_rate": 0.02, "wander_time": 20.0}, seed=2)
    rooms = set()
    for _ in range(400):
        world.step()
        rooms |= {(p["id"], p["room"]) for p in world.snapshot_dict()["people"]}
    away = {(p, r) for p, r in rooms if r in ("r-5302", "r-5310")}
    assert away, "nobody went to the kitchen or lounge in 200 s"
    assert all(p["room"] == p["office"] or p["room"] in ("r-5302", "r-5310")
               for p in world.snapshot_dict()["people"])
