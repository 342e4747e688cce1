"""The office world over the real processes: `teleo launch scenarios/office_errand.toml` runs
the world, perception, inference, executive and goal-entry processes on zenoh in lockstep,
and the primitive-skill errand delivers the mail (seed 003's domain)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from e2e_helpers import ROOT, Teleo

SCENARIO = ROOT / "scenarios" / "office_errand.toml"


@pytest.fixture(scope="module")
def errand(tmp_path_factory):
    folder = tmp_path_factory.mktemp("office")
    done = Teleo(folder)("launch", str(SCENARIO), "--summary", str(folder / "summary.json"),
                         "--render", str(folder / "run.png"), timeout=240)
    return folder, done


def test_the_errand_is_delivered_over_the_real_processes(errand):
    folder, done = errand
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["completed"] and summary["cycles"] == 200 and summary["domain"] == "office"
    assert [(g["goal"], g["status"]) for g in summary["goals"]] == [
        ("(delivered mail-reid reid)", "achieved")]
    assert summary["achievements"]["ME"]["deliveries"] == 1
    assert summary["law_violations"]["ME"] == {"bumps": 0}
    assert summary["counters"]["ME"]["travel_cm"] > 7000
    assert "goals achieved: 1 of 1" in done.stdout
    assert (folder / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_the_trace_shows_the_errands_commands_and_matches_simulate(errand):
    folder, _ = errand
    summary = json.loads((folder / "summary.json").read_text())
    lines = [json.loads(x) for x in Path(summary["trace"]).read_text().splitlines()]
    assert [x["cycle"] for x in lines] == list(range(200))
    steps, last = [], None
    for line in lines:
        if line["actions"]["ME"] != last:
            last = line["actions"]["ME"]
            steps.append(last)
    assert steps == [[["*goto", "r-5313"]], [["*acquire", "mail-reid", "khaigh"]],
                     [["*goto", "r-5315"]], [["*deliver", "mail-reid", "reid"]], []]
    from tools.commands.simulate import simulate
    from world.run_scenario import load_scenario

    run = simulate(load_scenario(SCENARIO))
    assert [line["actions"]["ME"] for line in lines] == [r["ME"]["actions"] for r in run.records]
