"""Perception from a snapshot dict (the perception process's path, no object per row) gives the
rows perception from a WorldSnapshot gives, and the buildings' and packages' rows it works out
in shortcuts (the two nearest corners, a route searched once per edge) are what the plain
definitions give: every corner's polar sorted, and navigation.guide."""

from __future__ import annotations

import copy
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from world_helpers import QUIET, car, snapshot

from world.driving.city import build_city
from world.driving.navigation import current_edge, guide
from world.driving.perception import perceive, perceive_dict, polar
from world.driving.snapshot import PackageState, PedState
from world.errors import WorldError

CITY = build_city(QUIET)
SEGMENTS = [s.id for s in CITY.segments]
ADDRESSES = [(b.street, b.address) for b in CITY.buildings]


def rows(percepts: list[list], kind: str) -> dict[str, dict]:
    return {p[1]: dict(zip(p[2::2], p[3::2], strict=True)) for p in percepts if p[0] == kind}


def r3(v: float) -> float:
    return round(float(v), 3) + 0.0


def buildings_by_definition(me, reach: float) -> dict[str, dict]:
    """Each building whose nearest corner is in range, its two nearest corners by sorting
    every corner's polar (dist, angle)."""
    out = {}
    for b in CITY.buildings:
        (d1, a1), (d2, a2) = sorted(polar(me, x, y) for x, y in b.corners)[:2]
        if d1 <= reach:
            out[b.id] = {"address": b.address, "street": b.street, "c1angle": r3(a1),
                         "c1dist": r3(d1), "c2angle": r3(a2), "c2dist": r3(d2)}
    return out


coord = st.floats(-60.0, 360.0, allow_nan=False)
heading = st.floats(-179.9, 180.0, allow_nan=False)


@settings(max_examples=150, deadline=None)
@given(x=coord, y=coord, h=heading, others=st.lists(st.tuples(coord, coord), max_size=4),
       blocked=st.sets(st.sampled_from(SEGMENTS), max_size=6),
       addresses=st.lists(st.sampled_from(ADDRESSES), min_size=1, max_size=3, unique=True))
def test_the_dict_path_gives_the_rows_of_the_object_path_and_of_the_definitions(
        x, y, h, others, blocked, addresses) -> None:
    me = car(x, y, h)
    peds = tuple(PedState(f"P{i}", px, py, 0.0, 1.0, "walk") for i, (px, py) in enumerate(others))
    packages = tuple(PackageState(f"K{i}", a, s, "ME") for i, (s, a) in enumerate(addresses))
    snap = snapshot(me, car(y, x, -h, ident="T1", kind="traffic"), peds=peds,
                    packages=packages, blocked=tuple(sorted(blocked)))
    got = perceive_dict(snap.to_dict(), "ME")
    assert got == perceive(snap, "ME")
    assert rows(got, "building") == buildings_by_definition(me, QUIET.perception_range)
    edge = current_edge(CITY, x, y, h)
    for p in packages:
        row = rows(got, "package")[p.id]
        if edge is None:
            assert (row["next-turn"], row["turn-dist"]) == ("NONE", 0.0)
            continue
        seg, d = edge
        g = guide(CITY, seg, d, seg.local(x, y)[0], CITY.building(p.street, p.address),
                  frozenset(blocked))
        assert (row["next-turn"], row["turn-dist"]) == (g.turn, r3(g.dist))


def test_corners_as_near_as_each_other_are_ordered_by_their_angles() -> None:
    b = CITY.buildings[0]
    (x1, y1), (x2, y2) = b.corners[:2]   # its front corners: the car faces their middle
    mx, my = (x1 + x2) / 2, (y1 + y2) / 2
    for hx in (0.0, 90.0, -90.0, 180.0, 45.0):
        me = car(mx + (mx - b.disc[0]) * 0.5, my + (my - b.disc[1]) * 0.5, hx)
        got = rows(perceive_dict(snapshot(me).to_dict(), "ME"), "building")
        assert got[b.id] == buildings_by_definition(me, QUIET.perception_range)[b.id]
        assert got[b.id]["c1dist"] == got[b.id]["c2dist"]


@pytest.mark.parametrize(("spoil", "named"), [
    (lambda d: d["cars"][0].update(x="east"), "cars[0].x"),
    (lambda d: d["pedestrians"][0].update(speed=float("nan")), "pedestrians[0].speed"),
    (lambda d: d["packages"][0].update(colour="red"), "packages[0]"),
    (lambda d: d.pop("blocked"), "blocked"),
])
def test_a_snapshot_not_of_the_schema_is_refused_naming_the_field(spoil, named) -> None:
    d = snapshot(car(50.0, -2.0, 0.0), peds=(PedState("P1", 60.0, 8.0, 0.0, 1.0, "walk"),),
                 packages=(PackageState("K1", 3, "FIRST", "ME"),)).to_dict()
    spoil(d)
    with pytest.raises(WorldError, match="snapshot: " + re.escape(named)):
        perceive_dict(d, "ME")


def test_an_agent_without_a_car_is_refused_naming_the_cars() -> None:
    d = snapshot(car(50.0, -2.0, 0.0)).to_dict()
    with pytest.raises(WorldError, match=r"snapshot of cycle 7: no car 'YOU'; cars: \['ME'\]"):
        perceive_dict(d, "YOU")


def test_one_snapshot_read_by_several_agents_gives_each_its_own_and_a_spoilt_copy_fails() -> None:
    """A shared process hands one snapshot dict to each of its agents' perception (the
    schema is checked once for it, world/base.py `rebuild`): each agent still gets the
    percepts a fresh copy gives it, and a spoilt copy read right after is refused."""
    d = snapshot(car(50.0, -2.0, 0.0), car(80.0, -2.0, 180.0, ident="YOU")).to_dict()
    seen = [perceive_dict(d, agent) for agent in ("ME", "YOU", "ME")]
    fresh = [perceive_dict(copy.deepcopy(d), agent) for agent in ("ME", "YOU")]
    assert seen == [fresh[0], fresh[1], fresh[0]] and fresh[0] != fresh[1]
    spoilt = copy.deepcopy(d)
    spoilt["cars"][1]["speed"] = "fast"
    with pytest.raises(WorldError, match=re.escape("snapshot: cars[1].speed")):
        perceive_dict(spoilt, "ME")
