"""`teleo launch scenarios/pddl/sussman.toml`: a PDDL problem in the pddl world over the real
processes (world, perception, inference, executive, goal entry) on zenoh, in lockstep; the
actions the trace records replay, under pyperplan's reading of the files, to the goal."""

from __future__ import annotations

import json
from pathlib import Path

from e2e_helpers import ROOT, Teleo
from pyperplan.grounding import ground
from pyperplan.pddl.parser import Parser

SUSSMAN = ROOT / "scenarios" / "pddl" / "sussman.toml"
FILES = (ROOT / "scenarios" / "pddl" / "blocks-domain.pddl",
         ROOT / "scenarios" / "pddl" / "sussman.pddl")


def test_the_sussman_anomaly_over_the_processes(tmp_path):
    done = Teleo(tmp_path)("launch", str(SUSSMAN), "--summary", str(tmp_path / "summary.json"),
                           "--render", str(tmp_path / "run.png"), timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["completed"] and summary["domain"] == "pddl"
    assert [(g["goal"], g["status"]) for g in summary["goals"]] == \
        [("(and (on a b) (on b c))", "achieved")]
    lines = [json.loads(x) for x in Path(summary["trace"]).read_text().splitlines()]
    acted = [a for line in lines for a in line["actions"]["ME"] if a != ["*wait"]]
    parser = Parser(str(FILES[0]), str(FILES[1]))
    task = ground(parser.parse_problem(parser.parse_domain()))
    ops = {op.name: op for op in task.operators}
    state = task.initial_state
    for a in acted:
        op = ops[f"({a[0][1:]} {' '.join(a[1:])})"]
        assert op.applicable(state), a
        state = op.apply(state)
    assert task.goal_reached(state) and len(acted) == 6
    assert (tmp_path / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
