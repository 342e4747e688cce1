"""The blocks scenarios run through tools.commands.simulate.simulate, the same pure pieces the
processes run: Figure 3 of seed 000 on programs/blocks.tlp, and a random tower problem."""

from __future__ import annotations

from pathlib import Path

import pytest

from agents.lang import Engine, load_program
from tools.commands.scenario_check import load_checked
from tools.commands.simulate import simulate
from world.blocks import perceive

ROOT = Path(__file__).resolve().parents[3]


@pytest.fixture(scope="module")
def figure3():
    scenario, _ = load_checked(ROOT / "scenarios" / "blocks_figure3.toml")
    return scenario, simulate(scenario)


def test_figure3_unstacks_c_puts_it_down_and_unstacks_b(figure3):
    """Seed 000, Figure 3: (*unstack C B), (*putdown C T), (*unstack B A)."""
    _, run = figure3
    done = [r["ME"]["actions"] for r in run.records if r["ME"]["actions"]]
    assert done == [[["*unstack", "C", "B"]], [["*putdown", "C", "T"]],
                    [["*unstack", "B", "A"]]]
    assert run.final["counters"]["ME"] == {"actions_done": 3, "actions_failed": 0,
                                           "blocks_moved": 1, "blocks_dropped": 0}


def test_figure3_ends_with_a_clear_and_b_in_the_hand(figure3):
    scenario, run = figure3
    engine = Engine(load_program(scenario.agents[0].program))
    beliefs = {str(b) for b in engine.infer(perceive(run.final, "ME"))}
    assert {"(clear A)", "(holding B)", "(ontable C T)", "(ontable A T)"} <= beliefs
    assert dict(run.records[-1]["ME"]["goals"])["g1"] in ("satisfied", "achieved")


def test_the_random_scenario_puts_every_block_on_the_table():
    scenario, _ = load_checked(ROOT / "scenarios" / "blocks_random.toml")
    run = simulate(scenario)
    blocks = [p for p in perceive(run.final, "ME") if p[0] == "block"]
    assert len(blocks) == 6 and all(p[5] == 2 for p in blocks)
    assert run.final["counters"]["ME"]["blocks_moved"] >= 1
    assert dict(run.records[-1]["ME"]["goals"])["g1"] in ("satisfied", "achieved")


def test_the_mishaps_drill_reports_the_slip_and_the_falls_and_a_is_cleared():
    scenario, _ = load_checked(ROOT / "scenarios" / "blocks_mishaps.toml")
    run = simulate(scenario, keep_every=1)
    events = [(e["kind"], e.get("block"), e.get("agent")) for s in run.snapshots
              for e in s["events"] if e["kind"] != "injected"]
    assert events[0] == ("dropped", "C", "ME")
    assert ("fell", "W", "") in events and ("fell", "N", "") in events
    assert run.final["counters"]["ME"]["blocks_dropped"] == 1
    acted = [a for r in run.records for a in r["ME"]["actions"]]
    assert acted[:2] == [["*unstack", "C", "B"], ["*unstack", "B", "A"]]
    engine = Engine(load_program(scenario.agents[0].program))
    assert "(clear A)" in {str(b) for b in engine.infer(perceive(run.final, "ME"))}
