"""Scenario files: what `teleo launch` reads, and the errors a typo gets."""

from __future__ import annotations

from pathlib import Path

import pytest

from world.run_scenario import Mode, ScenarioError, load_scenario, scenario_from_dict

ROOT = Path(__file__).resolve().parents[2]


def test_the_driving_demo_scenario_loads():
    scenario = load_scenario(ROOT / "scenarios" / "driving_demo.toml")
    assert scenario.run.mode is Mode.LOCKSTEP
    assert scenario.agent_ids == ["ME"]
    # found from any working directory: the programs/ folder above the scenario
    assert scenario.agent("ME").program == ROOT / "programs" / "driving.tlp"
    goals = [(g.goal, g.at_cycle) for g in scenario.goals]
    assert goals[0] == ("(package-delivered PACKET1)", 0)
    assert goals[1][0] == "(package-delivered PACKET2)" and goals[1][1] > 0


def test_fixture_program_resolves_beside_the_scenario():
    scenario = load_scenario(ROOT / "tests" / "e2e" / "fixtures" / "hold_speed.toml")
    assert scenario.agent("ME").program.exists()


def minimal(**extra):
    doc = {"agents": [{"id": "ME", "program": "p.tlp"}]}
    doc.update(extra)
    return doc


def test_defaults_and_events():
    doc = minimal(events=[{"at_cycle": 3, "kind": "pedestrian", "x": 1.0}])
    scenario = scenario_from_dict(doc, Path("s.toml"))
    assert scenario.run.cycles == 100 and scenario.run.seed == 0
    assert scenario.events[0].event == {"kind": "pedestrian", "x": 1.0}
    assert scenario.agent("ME").max_restarts("inference") == 3


@pytest.mark.parametrize("doc, message", [
    ({"agents": []}, "at least one agent"),
    (minimal(run={"mode": "fast"}), r"\[run\].mode: expected 'lockstep' or 'realtime'"),
    (minimal(run={"cycles": "ten"}), r"\[run\].cycles: expected int"),
    (minimal(run={"speed": 3}), r"unknown field\(s\) \['speed'\]"),
    (minimal(goals=[{"agent": "YOU", "goal": "(x)"}]), r"agent: expected one of \['ME'\]"),
    (minimal(goals=[{"op": "cancel"}]), "a cancel needs the goal id"),
    ({"agents": [{"id": "ME", "program": "p", "respawn": {"planner": 1}}]}, "respawn"),
])
def test_mistakes_are_reported_with_the_field(doc, message):
    with pytest.raises(ScenarioError, match=message):
        scenario_from_dict(doc, Path("s.toml"))
