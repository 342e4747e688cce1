"""The planner picked by name in a scenario (`[[agents]] mechanism = "rogue"`): checked before
anything runs, passed by `teleo launch` to the executive process, used by `teleo simulate`."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.launch import process_specs
from tools.scenario_check import check_scenario
from world.run_scenario import ScenarioError, load_scenario, scenario_from_dict

ROOT = Path(__file__).resolve().parents[2]
FIGURE6 = ROOT / "scenarios" / "office_figure6.toml"


def test_the_mechanism_is_read_and_checked():
    scenario = load_scenario(FIGURE6)
    assert scenario.agent("ME").mechanism == "rogue"
    assert scenario.agent("ME").impasse_handler == "rogue"
    check_scenario(scenario)
    doc = {"world": {"domain": "office"},
           "agents": [{"id": "ME", "program": str(ROOT / "programs" / "office_rogue.tlp"),
                       "mechanism": "prodigy"}]}
    with pytest.raises(ScenarioError, match="agent ME: mechanism: expected one of "
                                            r"\['means-ends', 'rogue'\], got 'prodigy'"):
        check_scenario(scenario_from_dict(doc, Path("x.toml")))
    doc["agents"][0]["mechanism"] = 3
    with pytest.raises(ScenarioError, match=r"\.mechanism: expected str, got 3"):
        scenario_from_dict(doc, Path("x.toml"))
    doc["agents"][0].update(mechanism="rogue", solver=False)
    assert scenario_from_dict(doc, Path("x.toml")).agent("ME").impasse_handler is None


def test_launch_passes_the_mechanism_to_the_executive(tmp_path):
    specs = {s.name: s for s in process_specs(load_scenario(FIGURE6), "r", tmp_path, [], 10,
                                               1, "lockstep")}
    argv = specs["ME.executive"].argv
    assert argv[argv.index("--mechanism") + 1] == "rogue"
    errand = load_scenario(ROOT / "scenarios" / "office_errand.toml")
    plain = {s.name: s for s in process_specs(errand, "r", tmp_path, [], 10, 1, "lockstep")}
    assert "--mechanism" not in plain["ME.executive"].argv
