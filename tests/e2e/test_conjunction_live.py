"""A conjunctive goal posted live (issue 22): `teleo goal post '(and (on A B) (on B C))'` to a
running Blocks World launch (world, perception, inference, executive and goal entry as real
processes on zenoh, pymunk physics, lockstep) is validated by the goal-entry process, carried
as text on the bus, pursued by the executive conjunct by conjunct and reported achieved, as
written, by `teleo goal list`: the Sussman anomaly in its six actions."""

from __future__ import annotations

import json
from pathlib import Path

from e2e_helpers import FIXTURES, interrupt, wait_for

SUSSMAN = FIXTURES / "blocks_sussman.toml"
GOAL = "(and (on A B) (on B C))"


def _actions(info: dict) -> list[list]:
    path = Path(info["run_dir"]) / "trace.jsonl"
    lines = [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []
    return [a for line in lines for a in line["actions"].get("ME", [])]


def _listed(teleo) -> list[dict]:
    done = teleo("goal", "list", "--json")
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_a_conjunction_posted_live_is_achieved_as_written(teleo):
    launcher = teleo.start("launch", str(SUSSMAN))
    try:
        info = teleo.run_info()
        bad = teleo("goal", "post", "(and (on A B) (onn B C))", "-p", "1")
        assert bad.returncode == 1 and "undefined concept 'onn'" in bad.stderr, bad.stderr
        posted = teleo("goal", "post", GOAL, "-p", "1")
        assert posted.returncode == 0 and "posted g1 for ME" in posted.stdout, posted.stderr
        assert wait_for(lambda: [(g["goal"], g["status"]) for g in _listed(teleo)] ==
                        [(GOAL, "achieved")], 120), teleo.launch_output()
        listed = teleo("goal", "list")
        assert GOAL in listed.stdout and "achieved" in listed.stdout
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    assert _actions(info) == [["*unstack", "C", "A"], ["*putdown", "C", "T"],
                              ["*pickup", "B", "T"], ["*stack", "B", "C"],
                              ["*pickup", "A", "T"], ["*stack", "A", "B"]]
