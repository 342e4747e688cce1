"""`teleo check SCENARIO` warns of a goal whose instances, in the world the scenario starts
with, include one that no skill or concept can make true (issue 31: ``(on D ?x)`` includes
``(on D D)``), naming the goal and the conjunction form for "some instance"; the check still
passes, and the scenarios shipped get no such warning."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from tools.cli import cli

ROOT = Path(__file__).resolve().parents[2]
TOML = """
[run]
name = "bw"
mode = "lockstep"
cycles = 10
seed = 0

[world]
domain = "blocks"
towers = [["C", "A"], ["B"], ["D"]]

[[agents]]
id = "ME"
program = "{program}"

[[goals]]
agent = "ME"
goal = "(and (on A B) (on B C))"
priority = 5

[[goals]]
agent = "ME"
goal = "(on D ?x)"
priority = 6
"""


def test_check_warns_of_an_instance_nothing_can_make_true(tmp_path):
    path = tmp_path / "bw.toml"
    path.write_text(TOML.format(program=ROOT / "programs" / "blocks.tlp"))
    result = CliRunner().invoke(cli, ["check", "--json", str(path)])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert doc["ok"] is True
    messages = [w["message"] for w in doc["files"][0]["warnings"]]
    assert messages == [
        "[[goals]] #2: (on D ?x) means every instance, and its instances include (on D D), "
        "which no skill or concept can make true (left out when the agent pursues it); for "
        "some instance, write (and (on D ?x))"]


def test_the_shipped_blocks_scenarios_get_no_such_warning():
    paths = sorted(str(p) for p in (ROOT / "scenarios").glob("blocks_*.toml"))
    result = CliRunner().invoke(cli, ["check", "--json", *paths])
    assert result.exit_code == 0, result.output
    for f in json.loads(result.stdout)["files"]:
        assert not any("means every instance" in w["message"] for w in f["warnings"])
