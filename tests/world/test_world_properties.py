"""Property tests: actions never raise, percepts are always neutral and well-signed,
navigation always has an answer on an open grid."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st
from world_helpers import car, snapshot

from world.driving.city import build_city
from world.driving.config import WorldConfig
from world.driving.navigation import guide
from world.driving.perception import perceive
from world.driving.snapshot import PackageState
from world.driving.vehicle import Controls, apply_action

values = st.one_of(st.none(), st.booleans(), st.integers(-1000, 1000),
                   st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=4))
actions = st.one_of(values, st.lists(st.one_of(st.sampled_from(
    ["*cruise", "*gas", "*brake", "*straighten", "*steer", "*fly"]), values), max_size=3))


@given(actions)
def test_any_action_gives_an_outcome_and_keeps_controls_in_range(action: object) -> None:
    c = Controls()
    outcome = apply_action(c, action)
    assert outcome["status"] in ("done", "failed")
    assert (outcome["reason"] == "") == (outcome["status"] == "done")
    assert 0 <= c.throttle <= 100 and 0 <= c.brake <= 100 and -40 <= c.wheel <= 40


@settings(max_examples=60, deadline=None)
@given(st.floats(-40, 340), st.floats(-40, 340), st.floats(-180, 180))
def test_percepts_are_neutral_and_well_formed_anywhere(x: float, y: float, h: float) -> None:
    snap = snapshot(car(x, y, h), packages=(PackageState("P1", 7, "C", "ME"),))
    percepts = perceive(snap, "ME")
    for p in percepts:
        assert len(p) % 2 == 0 and all(type(v) in (str, int, float) for v in p)
        if p[0] == "lane-line":
            assert -90.0 < p[7] <= 90.0
        if p[0] in ("man", "car", "intersection"):
            assert p[p.index("dist") + 1] <= snap.config.perception_range
    (pkg,) = [p for p in percepts if p[0] == "package"]
    assert pkg[pkg.index("next-turn") + 1] in ("LEFT", "RIGHT", "STRAIGHT", "ARRIVING")


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 23), st.sampled_from([1, -1]), st.floats(0, 100),
       st.integers(0, 95))
def test_every_address_is_reachable_without_u_turns(seg_k: int, d: int, along: float,
                                                    building_k: int) -> None:
    city = build_city(WorldConfig())
    g = guide(city, city.segments[seg_k], d, along, city.buildings[building_k])
    assert g.turn in ("LEFT", "RIGHT", "STRAIGHT", "ARRIVING")
