"""The planner picked by name in a scenario (`[[agents]] mechanism = "rogue"`): checked before
anything runs, passed by `teleo launch` to the executive process, used by `teleo simulate`."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.commands.scenario_check import check_scenario
from tools.launching.run_plan import Plan, process_specs, select
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


def specs_of(scenario, folder: Path) -> dict:
    """The processes `teleo launch` would start for `scenario` (tools/launching/run_plan.py)."""
    plan = Plan(scenario, "r", folder, 10, 1, "lockstep", select(scenario, None),
                endpoint="tcp/127.0.0.1:7447")
    return {s.name: s for s in process_specs(plan)}


def test_launch_passes_the_mechanism_to_the_executive(tmp_path):
    specs = specs_of(load_scenario(FIGURE6), tmp_path)
    argv = specs["ME.executive"].argv
    assert argv[argv.index("--mechanism") + 1] == "rogue"
    errand = load_scenario(ROOT / "scenarios" / "office_errand.toml")
    plain = specs_of(errand, tmp_path)
    assert "--mechanism" not in plain["ME.executive"].argv
