"""The shipped driving scenarios, run whole in one process (tools/simulate.py): every errand
delivered, no law broken (world/driving/percepts.md, counters)."""

from __future__ import annotations

import pytest

from tests.driving.scenarios import final, shipped
from tools.simulate import simulate

LAWS = ("pedestrian_hits", "vehicle_collisions", "off_road", "yellow_crossings",
        "speeding_cycles")


def violations(run, agent: str = "ME") -> dict[str, int]:
    return {k: final(run).counters[agent][k] for k in LAWS if final(run).counters[agent][k]}


def test_the_demo_delivers_both_packages_and_breaks_no_law():
    run = simulate(shipped("driving_demo.toml"))
    assert [p.id for p in final(run).packages if p.delivered] == ["PACKET1", "PACKET2"]
    assert violations(run) == {}


def test_a_third_package_round_the_edge_of_town_breaks_no_law():
    """issue 12, item 9: the flat program crossed the yellow line at I9 on this route."""
    run = simulate(shipped("driving_demo_packet3.toml"))
    assert [p.id for p in final(run).packages if p.delivered] == ["PACKET1", "PACKET2",
                                                                  "PACKET3"]
    assert violations(run) == {}


@pytest.mark.parametrize("seed", [1, 2])
def test_busy_streets_break_no_law(seed):
    run = simulate(shipped("busy_streets.toml"), seed=seed)
    assert [p.id for p in final(run).packages if p.delivered] == ["PACKET1", "PACKET2"]
    assert violations(run) == {}
