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
