"""The robot's navigator (seed 003 §6, navigateToG): shortest routes through the corridors,
replanning around doors it sees shut, failures with their reasons (closed or blocked door,
bump, lack of progress) and the injectable false success."""

from __future__ import annotations

import json

import pytest
from office_helpers import events, office, percept, robot, until_done

from world.office.floor import build_floor
from world.office.routes import plan


def _planned(world, room: str) -> float:
    r = robot(world)
    return plan(build_floor(world.config), (r["x"], r["y"]), room).length


def test_goto_drives_the_shortest_route_into_the_room():
    world = office()
    expected = _planned(world, "r-5303")          # lab r-5306 round the west end: 40 m
    cycles, out = until_done(world, ["*goto", "r-5303"], every_cycle=True)
    assert out == {"action": ["*goto", "r-5303"], "status": "done", "reason": ""}
    me = robot(world)
    assert me["place"] == "r-5303" and me["speed"] == 0.0
    assert expected == pytest.approx(40.0)
    assert me["travelled"] == pytest.approx(expected, abs=1.0)   # corners are cut by < 0.15 m
    assert world.snapshot_dict()["counters"]["ME"]["travel_cm"] == round(me["travelled"] * 100)
    assert cycles == pytest.approx(expected / (1.0 * 0.5), abs=3)  # 1 m/s, 0.5 s a cycle
    assert percept(world, "robot", "ME")["room"] == "r-5303"
    op = percept(world, "operation", "ME")
    assert (op["action"], op["target"], op["status"], op["reason"]) == \
        ("goto", "r-5303", "done", "NIL")


def test_a_goto_sent_once_runs_to_its_end_and_reports_once():
    world = office()
    outcomes = world.apply_actions("ME", [["*goto", "r-5304"]])
    seen = list(outcomes)
    for _ in range(60):
        world.step()
        seen += world.apply_actions("ME", [])
    assert seen == [{"action": ["*goto", "r-5304"], "status": "done", "reason": ""}]
    assert robot(world)["place"] == "r-5304"


def test_progress_is_perceived_while_the_goto_runs():
    world = office()
    world.apply_actions("ME", [["*goto", "r-5318"]])
    world.step()
    op = percept(world, "operation", "ME")
    assert (op["status"], op["ended"]) == ("running", -1)
    me = percept(world, "robot", "ME")
    assert me["moving"] == "T" and me["speed"] == pytest.approx(1.0)


def test_a_goto_to_the_room_it_is_in_is_done_at_once():
    world = office()
    assert world.apply_actions("ME", [["*goto", "r-5306"]]) == [
        {"action": ["*goto", "r-5306"], "status": "done", "reason": ""}]


def test_a_fire_door_seen_blocked_on_the_way_makes_it_go_round():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    direct = _planned(world, "r-5313")
    world.inject({"kind": "block", "door": "d-south"})      # the navigator does not know yet
    _, out = until_done(world, ["*goto", "r-5313"])
    assert out["status"] == "done" and robot(world)["place"] == "r-5313"
    counters = world.snapshot_dict()["counters"]["ME"]
    assert counters["reroutes"] == 1 and counters["failures"] == 0
    assert robot(world)["travelled"] > direct + 20
    assert percept(world, "door", "d-south")["state"] == "blocked"


def test_a_closed_door_into_the_goal_fails_the_goto_with_the_door_named():
    world = office({"robots": [{"agent": "ME", "room": "r-5309"}]})
    world.inject({"kind": "close", "door": "d-5313"})
    _, out = until_done(world, ["*goto", "r-5313"])
    assert out["status"] == "failed"
    assert out["reason"].startswith("ME: (*goto r-5313): door-closed: d-5313 is closed; ")
    me = robot(world)
    assert me["place"] == "c-south" and me["speed"] == 0.0
    assert percept(world, "operation", "ME")["reason"] == "door-closed"
    door = percept(world, "door", "d-5313")
    assert (door["state"], door["visible"]) == ("closed", "T")
    room = percept(world, "room", "r-5313")
    assert (room["reachable"], room["dist"]) == ("NIL", -1.0)
    # asked again, the navigator knows: no route at once
    again = world.apply_actions("ME", [["*goto", "r-5313"]])
    assert again[0]["status"] == "failed" and "door-closed" in again[0]["reason"]
    assert world.snapshot_dict()["counters"]["ME"]["failures"] == 2


def test_a_blocked_door_into_the_goal_fails_with_door_blocked():
    world = office({"robots": [{"agent": "ME", "room": "r-5309"}]})
    world.inject({"kind": "block", "door": "d-5311"})
    _, out = until_done(world, ["*goto", "r-5311"])
    assert "door-blocked: d-5311 is blocked" in out["reason"]


def test_an_unseen_obstacle_is_bumped_into_and_then_avoided():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    world.inject({"kind": "obstacle", "x": 20.0, "y": 9.0, "radius": 0.3})
    _, out = until_done(world, ["*goto", "r-5313"])
    assert out["status"] == "failed" and "bumped: touched obstacle o1 at" in out["reason"]
    assert world.snapshot_dict()["counters"]["ME"]["bumps"] == 1
    [bump] = events(world, "bump")
    assert bump["touched"] == "obstacle o1" and bump["x"] == pytest.approx(20.0 - 0.55, abs=0.2)
    assert percept(world, "obstacle", "o1")["radius"] == 0.3
    _, out = until_done(world, ["*goto", "r-5313"])
    assert out["status"] == "done" and robot(world)["place"] == "r-5313"
    assert world.snapshot_dict()["counters"]["ME"]["bumps"] == 1


def test_wheels_that_slip_end_the_goto_for_lack_of_progress():
    world = office()
    world.inject({"kind": "stall", "agent": "ME", "seconds": 30})
    cycles, out = until_done(world, ["*goto", "r-5310"])
    assert "no-progress: less than 0.1 m of progress in 5 s" in out["reason"]
    assert cycles == pytest.approx(10, abs=1)       # progress_time 5 s at 0.5 s a cycle


def test_a_false_success_reports_done_while_the_robot_is_elsewhere():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    assert world.inject({"kind": "false-success", "agent": "ME"})["status"] == "done"
    _, out = until_done(world, ["*goto", "r-5311"])
    assert out == {"action": ["*goto", "r-5311"], "status": "done", "reason": ""}
    op = percept(world, "operation", "ME")
    assert (op["target"], op["status"]) == ("r-5311", "done")
    assert percept(world, "robot", "ME")["room"] == "r-5313"     # the truth: next door
    assert world.snapshot_dict()["counters"]["ME"]["false_successes"] == 1
    [fault] = events(world, "false-success")
    assert (fault["target"], fault["actual"]) == ("r-5311", "r-5313")
    _, out = until_done(world, ["*goto", "r-5311"])                 # the fault was used up
    assert out["status"] == "done" and robot(world)["place"] == "r-5311"


def test_a_halfway_false_success_stops_in_the_corridor():
    world = office({"robots": [{"agent": "ME", "room": "r-5303"}]})
    world.inject({"kind": "false-success", "agent": "ME", "mode": "halfway"})
    _, out = until_done(world, ["*goto", "r-5317"])
    assert out["status"] == "done" and robot(world)["place"] == "c-south"


def test_a_robot_shut_in_its_room_has_no_route():
    world = office({"north": [{"id": "r-1", "door": "closed"}, "r-2"], "south": ["r-3"],
                    "fire_doors": [], "people": [], "items": [],
                    "robots": [{"agent": "ME", "room": "r-1"}]})
    [out] = world.apply_actions("ME", [["*goto", "r-3"]])
    assert out["status"] == "failed"
    assert "door-closed: no route from r-1 to r-3 (known: d-1 closed" in out["reason"]


def test_the_same_commands_give_the_same_run():
    def run() -> list[str]:
        world = office({"wander_rate": 0.05}, seed=4)
        world.inject({"kind": "block", "door": "d-north"})
        out = []
        for room in ("r-5313", "r-5302", "r-5318"):
            until_done(world, ["*goto", room])
            out.append(json.dumps(world.snapshot_dict(), sort_keys=True))
        return out
    assert run() == run()
