"""Seed 003's figures in the office world, in one process (tools/commands/simulate.py, the real
pymunk world): Figure 6 (a request merged with the rest of a plan under way), Figure 5 (both
requests at once: the order of least travel), Table 2 (a compatible request interleaved, an
incompatible one waiting), Figure 7 (the closest conference room first, then backtracking on
an occupied room)."""

from __future__ import annotations

import pytest

from agents.lang import load_program
from agents.lang.core.store import PerceptIndex
from agents.lang.engine import as_percepts
from agents.lang.planning.domain import Domain, Metric
from world.domain import get_domain

from .office_runs import FIGURE_6, ROOT, interleavings, run


@pytest.fixture(scope="module")
def figure6():
    return run("office_figure6")


@pytest.fixture(scope="module")
def figure5():
    return run("office_figure5")


def test_figure_6_the_second_request_is_merged_with_the_remaining_steps(figure6):
    assert figure6.executed() == FIGURE_6
    assert {r for _, r in figure6.results()} == {"verified"}
    assert [g for g in figure6.run.records[-1]["ME"]["goals"]] == [
        ("g1", "satisfied"), ("g2", "satisfied")]
    # jhm's request arrived at cycle 10, after <goto-pickup-loc mitchell r-5303> was sent
    # (cycle 0) and before it ended; it was planned at the next decision point
    head = figure6.planner.head
    assert head[0].sent == 0 and head[0].ended > 10
    assert "cycle 10: request g2 (delivered fax-jhm r-5313) (priority 5) added to the " \
           "pending goals" in figure6.log()
    # a single trip to r-5313, serving both requests
    assert [c for c in figure6.commands() if c[0] == "*goto"] == [
        ["*goto", "r-5303"], ["*goto", "r-5311"], ["*goto", "r-5313"]]
    assert head[4].tasks == ("g1", "g2")


def test_figure_6_travel_against_first_come_first_served(figure6):
    travel = figure6.planner.travel
    assert (travel.start, travel.route) == ("r-5306", ("r-5303", "r-5311", "r-5313"))
    assert (travel.executed_m, travel.fcfs_m) == (84.0, 103.0)
    odometer = figure6.counters()["travel_cm"] / 100
    assert abs(odometer - travel.executed_m) < 3.0


def test_figure_5_both_requests_at_once_give_the_order_of_least_travel(figure5):
    assert figure5.executed() == FIGURE_6
    # every interleaving of the two head-plans' places, by the world's distance percepts
    domain = get_domain("office")
    raw = domain.perceive(domain.create({}, 1, ["ME"]).snapshot_dict(), "ME")
    travel = Domain(load_program(ROOT / "programs" / "office_rogue.tlp")).travel
    metric = Metric(travel, PerceptIndex(as_percepts(raw)))
    lengths = {seq: metric.length("r-5306", list(seq))
               for seq in interleavings(("r-5303", "r-5313"), ("r-5311", "r-5313"))}
    assert min(lengths.values()) == 84.0 == figure5.planner.travel.executed_m
    assert max(lengths.values()) > 84.0


@pytest.fixture(scope="module")
def table2():
    return run("office_table2")


def test_table_2_a_compatible_request_is_interleaved_an_incompatible_one_waits(table2):
    steps = table2.executed()
    rich = [k for k, s in enumerate(steps) if "rich" in s]
    mmv = [k for k, s in enumerate(steps) if "mmv" in s]
    joseph = [k for k, s in enumerate(steps) if "joseph" in s]
    assert len(rich) == len(mmv) == len(joseph) == 4
    assert rich[1] < min(mmv) and max(mmv) < rich[2]      # on the way, between rich's steps
    assert min(joseph) > max(rich)                          # after the top one is done
    log = table2.log()
    waits = next(e for e in log if e.startswith("cycle 0: g3 waiting"))
    assert "adds" in waits and "g1" in waits
    assert any(e.startswith("cycle 0: g2 selected: compatible with g1: adds") for e in log)
    assert set(table2.statuses().values()) == {"achieved"}
    assert table2.planner.travel.executed_m < table2.planner.travel.fcfs_m


@pytest.fixture(scope="module")
def figure7():
    return run("office_figure7")


def test_figure_7_the_closest_conference_room_first_then_the_other(figure7):
    assert figure7.said() == ["Going to room 5309", "This room is occupied",
                              "Going to room 5311", "Meeting scheduled in room 5311"]
    assert [c for c in figure7.commands() if c[0] in ("*goto", "*observe")] == [
        ["*goto", "r-5309"], ["*observe", "r-5309"], ["*goto", "r-5311"],
        ["*observe", "r-5311"]]
    assert figure7.results() == [
        ("<goto-room r-5309>", "verified"), ("<select-conference-room r-5309>", "applied"),
        ("<observe-conference-room r-5309>", "not-achieved"),
        ("<goto-room r-5311>", "verified"), ("<select-conference-room r-5311>", "applied"),
        ("<observe-conference-room r-5311>", "verified"),
        ("<schedule-meeting r-5311>", "verified")]
    log = figure7.log()
    assert "cycle 0: rule fired: prefer bindings LOOK-AT-CLOSEST-CONF-ROOM-FIRST " \
           "(schedule-meeting r-5309) over (schedule-meeting r-5311)" in log
    assert any(e.endswith("rule fired: reject bindings AVOID-OCCUPIED-CONF-ROOMS "
                          "(schedule-meeting r-5309)") for e in log)
    assert figure7.statuses() == {"(mtg-scheduled)": "achieved"}
    assert "(meeting-in r-5311)" in figure7.planner.model
