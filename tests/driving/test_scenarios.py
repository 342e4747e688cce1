"""The shipped driving scenarios, run whole in one process (tools/commands/simulate.py): every
errand delivered, no law broken (world/driving/percepts.md, counters)."""

from __future__ import annotations

import pytest

from tests.driving.scenarios import final, goal, scenario, shipped
from tools.commands.simulate import simulate

LAWS = ("pedestrian_hits", "vehicle_collisions", "off_road", "yellow_crossings",
        "speeding_cycles")


def violations(run, agent: str = "ME") -> dict[str, int]:
    return {k: final(run).counters[agent][k] for k in LAWS if final(run).counters[agent][k]}


def test_the_demo_delivers_both_packages_and_breaks_no_law():
    run = simulate(shipped("driving_demo.toml"))
    assert [p.id for p in final(run).packages if p.delivered] == ["PACKET1", "PACKET2"]
    assert violations(run) == {}


def test_a_third_package_round_the_edge_of_town_breaks_no_law():
    """issue 12, item 9, as reported: the demo with PACKET3 at 8 THIRD posted at cycle 329. The
    flat program turned left at I9 (A/THIRD) and crossed A's yellow line at cycle 684; this
    program plans its own route, turns right there, and delivers all three lawfully."""
    run = simulate(shipped("driving_demo_packet3.toml"))
    assert [p.id for p in final(run).packages if p.delivered] == ["PACKET1", "PACKET2",
                                                                  "PACKET3"]
    assert violations(run) == {}


def headings_at(run, x: float, y: float, reach: float = 15.0) -> list[float]:
    """ME's heading [deg] in each cycle it is within ``reach`` [m] of the point (x, y)."""
    return [c["heading"] for s in run.snapshots for c in s["cars"]
            if c["id"] == "ME" and abs(c["x"] - x) < reach and abs(c["y"] - y) < reach]


def off(a: float, b: float) -> float:
    """The angle between headings a and b [deg], in 0..180."""
    return abs((a - b + 180) % 360 - 180)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_left_turn_at_the_edge_intersection_i9_keeps_right_of_the_yellow_line(seed):
    """issue 12, item 9, the manoeuvre itself: westbound on THIRD, moving off 40 m before I9
    (as after the demo's PACKET2 stop), left into A southbound for 7 A; pedestrians and
    traffic as in the demo."""
    start = {"agent": "ME", "street": "THIRD", "from": "B", "toward": "A", "along": 60.0}
    sc = scenario(cars=[start], packages=[{"id": "P1", "address": 7, "street": "A"}],
                  goals=[goal("(package-delivered P1)")], pedestrians=12, traffic=2,
                  cycles=320, seed=seed)
    run = simulate(sc, keep_every=1)
    turn = headings_at(run, 0.0, 200.0)                        # I9: A/THIRD, the city's corner
    assert off(turn[0], 180) < 5 and off(turn[-1], -90) < 5    # in westbound, out southbound
    assert [p.id for p in final(run).packages if p.delivered] == ["P1"]
    assert violations(run) == {}


@pytest.mark.parametrize("seed", [1, 2])
def test_busy_streets_break_no_law(seed):
    run = simulate(shipped("busy_streets.toml"), seed=seed)
    assert [p.id for p in final(run).packages if p.delivered] == ["PACKET1", "PACKET2"]
    assert violations(run) == {}
