"""Perception on hand-built snapshots: expected percepts, range limits, signs of angles/dists.

The default city: lettered streets A..D run north at x = 0, 100, 200, 300; FIRST..FOURTH run east
at y = 0, 100, 200, 300. S1 is FIRST between A and B; S16 is B between FIRST and SECOND.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from world_helpers import QUIET, car, snapshot

from world.driving.city import build_city
from world.driving.perception import perceive, polar
from world.driving.snapshot import PackageState, PedState
from world.errors import WorldError


def by_type(percepts: list[list], kind: str) -> dict[str, dict]:
    return {p[1]: dict(zip(p[2::2], p[3::2], strict=True)) for p in percepts if p[0] == kind}


def test_self_percept_in_the_right_lane_of_first_street() -> None:
    me = car(50.0, -2.0, 0.0, speed=12.5)
    (self_p,) = [p for p in perceive(snapshot(me), "ME") if p[0] == "self"]
    assert self_p == ["self", "ME", "speed", 12.5, "heading", 0.0, "wheel-angle", 0.0,
                      "throttle", 0.0, "limit", 15.0, "breakthrottle", 0.0, "segment", "S1",
                      "street", "FIRST", "x", 50.0, "y", -2.0]


def test_lane_lines_eastbound_yellow_on_the_left_white_on_the_right() -> None:
    lines = by_type(perceive(snapshot(car(50.0, -2.0, 0.0)), "ME"), "lane-line")
    assert set(lines) == {f"S1-{n}" for n in ("YELLOW", "WHITE1", "WHITE2", "SIDEWALK1",
                                              "SIDEWALK2")}
    assert lines["S1-YELLOW"] == {"color": "YELLOW", "dist": -2.0, "angle": 0.0, "segment": "S1"}
    assert lines["S1-WHITE2"]["dist"] == 2.0 and lines["S1-WHITE2"]["color"] == "WHITE"
    assert lines["S1-SIDEWALK2"]["dist"] == 4.0 and lines["S1-SIDEWALK1"]["dist"] == -8.0


def test_lane_lines_westbound_mirror_the_sides() -> None:
    lines = by_type(perceive(snapshot(car(50.0, 2.0, 180.0)), "ME"), "lane-line")
    assert lines["S1-YELLOW"]["dist"] == -2.0          # still on the car's left
    assert lines["S1-WHITE1"]["dist"] == 2.0           # the nearer white line on its right
    assert lines["S1-YELLOW"]["angle"] == 0.0


def test_line_angle_sign_says_which_way_to_steer() -> None:
    nose_left = by_type(perceive(snapshot(car(50.0, -2.0, 10.0)), "ME"), "lane-line")
    nose_right = by_type(perceive(snapshot(car(50.0, -2.0, -10.0)), "ME"), "lane-line")
    assert nose_left["S1-YELLOW"]["angle"] == -10.0     # line points to the car's right
    assert nose_right["S1-YELLOW"]["angle"] == 10.0     # line points to the car's left


def test_lines_follow_the_new_street_once_turned_past_45_degrees() -> None:
    before = by_type(perceive(snapshot(car(100.0, -2.0, 40.0)), "ME"), "lane-line")
    after = by_type(perceive(snapshot(car(100.0, -2.0, 50.0)), "ME"), "lane-line")
    assert {v["segment"] for v in before.values()} == {"S2"}      # FIRST, east of B
    assert {v["segment"] for v in after.values()} == {"S16"}      # B, north of FIRST
    assert after["S16-YELLOW"]["angle"] == 40.0


def test_self_segment_is_the_intersection_inside_one() -> None:
    self_p = by_type(perceive(snapshot(car(101.0, 1.0, 60.0)), "ME"), "self")["ME"]
    assert self_p["segment"] == "I2" and self_p["street"] == "B"


def test_pedestrian_ahead_left_has_positive_angle_and_range_limits() -> None:
    peds = (PedState("M1", 80.0, 8.0, 0.0, 0.0, "stand"),    # 30 m ahead, 10 m left
            PedState("M2", 60.0, -12.0, 0.0, 0.0, "stand"),  # 10 m ahead, 10 m right
            PedState("M3", 150.0, -2.0, 0.0, 0.0, "stand"))  # 100 m ahead: out of range
    men = by_type(perceive(snapshot(car(50.0, -2.0, 0.0), peds=peds), "ME"), "man")
    assert set(men) == {"M1", "M2"}
    assert men["M1"] == {"angle": round(math.degrees(math.atan2(10, 30)), 3),
                         "dist": round(math.hypot(30, 10), 3)}
    assert men["M2"]["angle"] == -45.0


def test_other_cars_in_range_with_their_speed() -> None:
    near = car(70.0, -2.0, 0.0, speed=7.0, ident="V1", kind="traffic")
    far = car(50.0, 98.0, 0.0, ident="V2", kind="traffic")
    cars = by_type(perceive(snapshot(car(50.0, -2.0, 0.0), near, far), "ME"), "car")
    assert cars == {"V1": {"angle": 0.0, "dist": 20.0, "speed": 7.0}}


def test_buildings_report_their_two_nearest_corners() -> None:
    buildings = by_type(perceive(snapshot(car(37.0, -2.0, 0.0)), "ME"), "building")
    b1 = buildings["B1"]      # FIRST 1: x 26..48, y 11..25, left of an eastbound car
    assert (b1["address"], b1["street"]) == (1, "FIRST")
    assert b1["c1dist"] == b1["c2dist"] == round(math.hypot(11, 13), 3)
    assert b1["c1angle"] > 0 and b1["c2angle"] > 0
    assert buildings["B2"]["c1angle"] < 0                     # FIRST 2 on the right
    assert all(b["c1dist"] <= QUIET.perception_range for b in buildings.values())


@given(st.floats(-60.0, 480.0), st.floats(-60.0, 480.0), st.floats(-180.0, 180.0))
@settings(max_examples=200, deadline=None)
def test_buildings_passed_over_by_distance_are_exactly_those_out_of_range(x, y, heading):
    """The disc test that skips far buildings changes nothing: every building whose nearest
    corner is within range is seen, with its two nearest corners, and no other."""
    me = car(x, y, heading)
    seen = by_type(perceive(snapshot(me), "ME"), "building")
    city = build_city(QUIET)
    expected = {}
    for b in city.buildings:
        (d1, _), _ = sorted(polar(me, cx, cy) for cx, cy in b.corners)[:2]
        if d1 <= QUIET.perception_range:
            expected[b.id] = round(d1, 3) + 0.0
    assert {k: v["c1dist"] for k, v in seen.items()} == expected


def test_streets_segments_and_intersections_in_range() -> None:
    percepts = perceive(snapshot(car(55.0, -2.0, 180.0)), "ME")   # westbound, range 50 m
    assert ["street", "FIRST"] in percepts and ["street", "B"] in percepts
    assert ["street", "A"] not in percepts and ["street", "C"] not in percepts
    inters = by_type(percepts, "intersection")
    assert set(inters) == {"I2"}                                   # I1 is 55 m away
    assert inters["I2"]["street"] == "FIRST" and inters["I2"]["cross"] == "B"
    # behind the car and 2 m north: on a westbound car's right -> negative
    assert inters["I2"]["angle"] == round(-(180 - math.degrees(math.atan2(2, 45))), 3)
    segs = by_type(percepts, "segment")
    assert segs["S1"] == {"street": "FIRST", "dist": 2.0, "blocked": "NIL", "from": "I1",
                          "to": "I2", "heading": 0.0, "length": 100.0}
    assert set(segs) == {"S1", "S2", "S16"}
    assert (segs["S16"]["from"], segs["S16"]["to"], segs["S16"]["heading"]) == ("I2", "I6", 90.0)
    assert (inters["I2"]["x"], inters["I2"]["y"]) == (100.0, 0.0)


def test_packages_are_always_seen_with_route_guidance() -> None:
    packages = (PackageState("P1", 5, "A", "ME"),        # far away, up street A
                PackageState("P2", 4, "FIRST", "ME"),    # ahead on the right of S1
                PackageState("P3", 1, "B", "YOU"))       # someone else's
    pk = by_type(perceive(snapshot(car(20.0, -2.0, 0.0), packages=packages), "ME"), "package")
    assert set(pk) == {"P1", "P2"}
    assert pk["P1"]["next-turn"] == "LEFT" and pk["P1"]["turn-dist"] == 80.0
    assert pk["P1"]["delivered"] == "NIL" and pk["P1"]["dist"] > QUIET.perception_range
    assert pk["P2"]["next-turn"] == "ARRIVING" and pk["P2"]["turn-dist"] == 43.0
    assert pk["P2"]["angle"] < 0                         # curb point on the car's right


def test_packages_say_where_their_address_is_served() -> None:
    """For route planning in a program: the curb point, and the lane that has the address on
    its right (its segment, heading and the intersection where its block begins)."""
    packages = (PackageState("P1", 5, "A", "ME"),        # A 5: west side, second block
                PackageState("P2", 4, "FIRST", "ME"))    # FIRST 4: south side, first block
    pk = by_type(perceive(snapshot(car(20.0, -2.0, 0.0), packages=packages), "ME"), "package")
    # odd addresses lie left of the axis (west of A, which points north): served southbound
    assert {k: pk["P1"][k] for k in ("segment", "heading", "entry", "entry-x", "entry-y")} == {
        "segment": "S14", "heading": -90.0, "entry": "I9", "entry-x": 0.0, "entry-y": 200.0}
    assert (pk["P1"]["x"], pk["P1"]["y"]) == (-5.0, 137.0)       # 37 m into its block
    assert {k: pk["P2"][k] for k in ("segment", "heading", "entry", "x", "y")} == {
        "segment": "S1", "heading": 0.0, "entry": "I1", "x": 63.0, "y": -5.0}
    assert math.hypot(63.0 - 20.0, -5.0 + 2.0) == pytest.approx(pk["P2"]["dist"], abs=1e-3)


def test_package_on_the_left_of_the_street_needs_a_loop() -> None:
    packages = (PackageState("P3", 3, "FIRST", "ME", delivered=True),)
    (p,) = by_type(perceive(snapshot(car(20.0, -2.0, 0.0), packages=packages), "ME"),
                   "package").values()
    assert p["next-turn"] != "ARRIVING" and p["delivered"] == "T"


def test_blocked_segment_is_perceived_and_avoided() -> None:
    packages = (PackageState("P1", 5, "A", "ME"),)
    snap = snapshot(car(20.0, -2.0, 0.0), packages=packages, blocked=("S1", "S16"))
    percepts = perceive(snap, "ME")
    assert by_type(percepts, "segment")["S1"]["blocked"] == "T"
    assert by_type(percepts, "package")["P1"]["next-turn"] != "LEFT"


def test_percepts_are_plain_neutral_lists() -> None:
    snap = snapshot(car(123.4, 57.8, 33.3), packages=(PackageState("P1", 5, "A", "ME"),))
    for p in perceive(snap, "ME"):
        assert isinstance(p, list) and isinstance(p[0], str)
        assert all(type(v) in (str, int, float) for v in p)


def test_unknown_agent_is_an_error_naming_it() -> None:
    with pytest.raises(WorldError, match="NOBODY"):
        perceive(snapshot(car(50.0, -2.0, 0.0)), "NOBODY")
