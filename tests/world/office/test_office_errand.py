"""The primitive-skill errand program (programs/office_errand.tlp) in the office world, run
in one process by tools.commands.simulate: go to the mail room, acquire the mail, deliver it."""

from __future__ import annotations

import tomllib
from pathlib import Path

from tools.commands.simulate import simulate
from world.run_scenario import load_scenario, scenario_from_dict

ROOT = Path(__file__).resolve().parents[3]
SCENARIO = ROOT / "scenarios" / "office_errand.toml"


def _changes(run, agent: str = "ME") -> list[tuple[int, list]]:
    """(cycle, actions) whenever the agent's actions change."""
    out, last = [], None
    for record in run.records:
        actions = record[agent]["actions"]
        if actions != last:
            out.append((record["cycle"], actions))
            last = actions
    return out


def test_the_errand_goes_to_the_mail_room_acquires_and_delivers():
    run = simulate(load_scenario(SCENARIO))
    steps = [actions for _, actions in _changes(run)]
    assert steps == [[["*goto", "r-5313"]], [["*acquire", "mail-reid", "khaigh"]],
                     [["*goto", "r-5315"]], [["*deliver", "mail-reid", "reid"]], []]
    counters = run.final["counters"]["ME"]
    assert (counters["deliveries"], counters["acquisitions"], counters["failures"],
            counters["bumps"]) == (1, 1, 0, 0)
    mail = next(i for i in run.final["items"] if i["id"] == "mail-reid")
    assert mail["holder"] == "reid"
    assert run.records[-1]["ME"]["goals"] == [("g1", "satisfied")]


def test_the_errand_runs_the_same_twice():
    scenario = load_scenario(SCENARIO)
    assert simulate(scenario, 120).records == simulate(scenario, 120).records


def test_the_errand_goes_the_other_way_round_a_blocked_fire_door():
    doc = tomllib.loads(SCENARIO.read_text())
    doc["events"] = [{"at_cycle": 0, "kind": "block", "door": "d-north"}]
    doc["run"]["cycles"] = 300
    doc["agents"][0]["program"] = str(ROOT / "programs" / "office_errand.tlp")
    run = simulate(scenario_from_dict(doc, SCENARIO))
    counters = run.final["counters"]["ME"]
    assert counters["deliveries"] == 1 and counters["reroutes"] == 1
    assert counters["travel_cm"] > simulate(load_scenario(SCENARIO)).final["counters"]["ME"][
        "travel_cm"]
