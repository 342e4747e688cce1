"""The office scenario files: checked whole, and the written-out floor is the default one."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from tools.commands.scenario_check import load_checked
from tools.commands.simulate import simulate
from world.office.config import load_office_config
from world.run_scenario import ScenarioError, scenario_from_dict

ROOT = Path(__file__).resolve().parents[3]
SCENARIOS = sorted((ROOT / "scenarios").glob("office_*.toml"))


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.name)
def test_every_office_scenario_is_checked_whole(path):
    scenario, programs = load_checked(path)
    assert scenario.domain == "office" and set(programs) == set(scenario.agent_ids)


def test_the_written_out_floor_is_the_default_floor():
    scenario, _ = load_checked(ROOT / "scenarios" / "office_floor.toml")
    written = load_office_config(scenario.world_table)
    assert replace(written, robots=()) == load_office_config({})


def test_the_floor_scenario_goes_the_other_way_round_the_blocked_fire_door():
    scenario, _ = load_checked(ROOT / "scenarios" / "office_floor.toml")
    counters = simulate(scenario).final["counters"]["ME"]
    assert (counters["deliveries"], counters["reroutes"], counters["failures"]) == (1, 1, 0)


def test_a_scripted_event_of_an_unknown_kind_is_refused_before_the_run(tmp_path):
    doc = {"world": {"domain": "office"},
           "agents": [{"id": "ME", "program": str(ROOT / "programs" / "office_errand.tlp")}],
           "events": [{"at_cycle": 3, "kind": "earthquake"}]}
    from tools.commands.scenario_check import check_scenario
    with pytest.raises(ScenarioError, match="kind: expected one of .*'false-success'"):
        check_scenario(scenario_from_dict(doc, tmp_path / "x.toml"))


def test_a_robot_start_for_someone_who_is_not_an_agent_is_refused(tmp_path):
    doc = {"world": {"domain": "office", "robots": [{"agent": "R2", "room": "r-5303"}]},
           "agents": [{"id": "ME", "program": str(ROOT / "programs" / "office_errand.tlp")}]}
    from tools.commands.scenario_check import check_scenario
    with pytest.raises(ScenarioError, match="robots: 'R2' is not an agent of this run"):
        check_scenario(scenario_from_dict(doc, tmp_path / "x.toml"))
