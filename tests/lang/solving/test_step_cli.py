"""`teleo step --json` on Figure 3 shows the goal stack under "solver", and a saved state
carries it to the next call (the same as a restarted executive)."""

from __future__ import annotations

import json

from click.testing import CliRunner

from tools.cli import cli

from ..conftest import ROOT
from ..test_blocks import TOWER, percepts


def test_step_shows_the_stack_and_goes_on_from_a_saved_state(tmp_path):
    seen = tmp_path / "figure3.json"
    seen.write_text(json.dumps(percepts(TOWER)))
    program, state = str(ROOT / "programs" / "blocks.tlp"), str(tmp_path / "state.json")
    runner = CliRunner()
    first = runner.invoke(cli, ["step", program, "--percepts", str(seen), "--json",
                                "--goal", "(clear A)", "--save-state", state])
    assert first.exit_code == 0, first.output
    solver = json.loads(first.output)["decision"]["solver"]
    assert [e["goal"] for e in solver["stacks"][0]["entries"]] == ["(clear A)",
                                                                   "(unstackable B A)"]
    assert solver["stacks"][0]["entries"][1]["why"] == \
        "chained off skill (unstack B A) because its start (unstackable B A) is false"
    second = runner.invoke(cli, ["step", program, "--percepts", str(seen), "--state", state])
    assert second.exit_code == 0, second.output
    assert "  3 (clear B)  <- decomposed (unstackable B A) through concept unstackable#1" in \
        second.output
    assert "actions: (*unstack C B)" in second.output


def test_step_takes_a_conjunctive_goal_and_shows_it_as_written(tmp_path):
    seen = tmp_path / "sussman.json"
    seen.write_text(json.dumps(percepts({"A": "T", "C": "A", "B": "T"})))
    program = str(ROOT / "programs" / "blocks.tlp")
    done = CliRunner().invoke(cli, ["step", program, "--percepts", str(seen), "--json",
                                    "--goal", "(and (on A B) (on B C)):3"])
    assert done.exit_code == 0, done.output
    goal = json.loads(done.output)["decision"]["goals"][0]
    assert (goal["goal"], goal["priority"], goal["status"], goal["instance"]) == (
        "(and (on A B) (on B C))", 3, "active", "(clear A)")
    assert json.loads(done.output)["decision"]["actions"] == [["*unstack", "C", "A"]]
    bad = CliRunner().invoke(cli, ["step", program, "--percepts", str(seen),
                                   "--goal", "(and (on A B) (on B))"])
    assert bad.exit_code != 0 and "concept on takes 2 argument(s), got 1 (conjunct (on B))" \
        in bad.output
