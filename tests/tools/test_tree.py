"""The decision tree (tools/records/tree.py) against golden files: each input is a recorded decision
(Decision.to_dict, as the intention channel carries it) and the expected ascii rendering and
JSON nodes beside it. Regenerate after an intended change with TELEO_UPDATE_GOLDEN=1 and
read the diff.

Inputs: the driving demo at cycle 0 (two goals acting through different resources, skills
passed over) and 370 (a law takes over, errands suspended), Figure 3 of seed 000 at cycle 0
(a path three skills deep), and a hand-made decision with every status, a skill passed over
below the top of a path, a goal with no skill, and a mechanism's section ("solver").
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from tools.records.tree import UNICODE, decision_tree, fold, render_text, to_json

GOLDEN = Path(__file__).with_name("golden")
CASES = sorted(p.stem for p in GOLDEN.glob("*.json") if p.suffixes == [".json"])


def _check(path: Path, text: str) -> None:
    if os.environ.get("TELEO_UPDATE_GOLDEN"):
        path.write_text(text)
    assert path.exists(), f"no golden file {path}: run with TELEO_UPDATE_GOLDEN=1"
    assert text == path.read_text()


@pytest.mark.parametrize("case", CASES)
def test_the_text_rendering_matches_the_golden_file(case: str) -> None:
    decision = json.loads((GOLDEN / f"{case}.json").read_text())
    _check(GOLDEN / f"{case}.txt", render_text(decision_tree(decision)) + "\n")


@pytest.mark.parametrize("case", CASES)
def test_the_json_nodes_match_the_golden_file(case: str) -> None:
    decision = json.loads((GOLDEN / f"{case}.json").read_text())
    _check(GOLDEN / f"{case}.tree.json", json.dumps(to_json(decision_tree(decision)),
                                                    indent=1) + "\n")


@pytest.mark.parametrize("case", CASES)
def test_the_brief_rendering_folds_what_goals_that_do_not_act_passed_over(case: str) -> None:
    decision = json.loads((GOLDEN / f"{case}.json").read_text())
    _check(GOLDEN / f"{case}.brief.txt", render_text(fold(decision_tree(decision))) + "\n")


def test_the_golden_cases_are_all_there() -> None:
    assert CASES == ["blocks_0", "driving_0", "driving_370", "mechanisms"]


def test_every_goal_and_action_of_the_decision_is_in_the_tree() -> None:
    for case in CASES:
        decision = json.loads((GOLDEN / f"{case}.json").read_text())
        text = render_text(decision_tree(decision))
        for goal in decision["goals"]:
            assert f"{goal['id']} {goal['status']}: {goal['goal']}" in text
        for action in decision["actions"]:  # numbers shown to 4 decimals
            shown = (repr(round(x, 4)) if isinstance(x, float) else str(x) for x in action)
            assert "(" + " ".join(shown) + ")" in text
        assert text.count("<- ") == len(decision["path"]) + len(decision["why"]) + sum(
            len(p["path"]) for p in decision["parallel"])


def test_the_acting_tip_of_each_path_is_marked() -> None:
    decision = json.loads((GOLDEN / "mechanisms.json").read_text())
    tips = [n for n in _nodes(decision_tree(decision)) if n.tip]
    assert [t.label for t in tips] == ["(*pickup A T)", "(*beep 0.5)"]
    assert "⇒ (*pickup A T)" in render_text(decision_tree(decision), UNICODE)


def _nodes(node):
    yield node
    for child in node.children:
        yield from _nodes(child)
