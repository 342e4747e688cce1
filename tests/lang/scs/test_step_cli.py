"""`teleo step PROGRAM --percepts F --outcomes F --state F --save-state F`: a body driven
cycle by cycle from the command line, the test playing the world's outcome reports."""

from __future__ import annotations

import json

from click.testing import CliRunner

from tests.lang.scs.drive import PRELUDE
from tools.cli import cli

BODY = "(do* (*a 1) (do-best (() :utility 5 (*b)) (() :utility 2 (*c))) (*e))"


def invoke(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_a_body_is_driven_cycle_by_cycle_with_outcomes(tmp_path):
    program = tmp_path / "body.tlp"
    program.write_text(PRELUDE + f"(skills ((never ?x) :percepts ((self ?x)) :body {BODY}))"
                       "\n(goals (never ME))\n")
    percepts = tmp_path / "p.txt"
    percepts.write_text("((self ME))")
    state, outcomes = tmp_path / "state.json", tmp_path / "outcomes.json"
    seen = []
    for cycle, status in enumerate(["done", "failed", "done", "done", "done"]):
        args = ["step", program, "--percepts", percepts, "--save-state", state, "--json"]
        if cycle:
            args += ["--state", state, "--outcomes", outcomes]
        result = invoke(*args)
        assert result.exit_code == 0, result.output
        out = json.loads(result.output)
        actions = out["decision"]["actions"]
        seen.append(actions)
        outcomes.write_text(json.dumps([{"action": a, "status": status, "reason": "stuck"
                                         if status == "failed" else ""} for a in actions]))
    # (*b) failed once: the do-best turns to (*c); then (*e), and the do* starts again
    assert seen == [[["*a", 1]], [["*b"]], [["*c"]], [["*e"]], [["*a", 1]]]
    shown = out["decision"]["scs"]
    assert {c["label"].split()[0]: c["factor"] for c in shown["choices"]} == \
        {"(*b)": 0.7, "(*c)": 1.0}
    assert shown["threads"][0]["status"] == "acting"
    text = invoke("step", program, "--percepts", percepts, "--state", state, "--outcomes",
                  outcomes).output
    assert "scs threads:" in text and "do-best discount factors:" in text


def test_bad_outcomes_are_reported_with_the_file(tmp_path):
    program = tmp_path / "body.tlp"
    program.write_text(PRELUDE + f"(skills ((never ?x) :percepts ((self ?x)) :body {BODY}))")
    percepts = tmp_path / "p.txt"
    percepts.write_text("((self ME))")
    bad = tmp_path / "o.json"
    bad.write_text('[{"action": ["*a"], "status": "maybe"}]')
    result = invoke("step", program, "--percepts", percepts, "--outcomes", bad)
    assert result.exit_code == 1
    assert f"{bad}: item 0: outcome" in result.output and "status: expected 'done' or " \
        "'failed', got 'maybe'" in result.output
