"""Search control rules (agents/lang/planning/control.py) at the goal decision point: seed
003's Table 2, SELECT-TOP-PRIORITY-AND-COMPATIBLE-GOALS, and reject/prefer goal rules."""

from __future__ import annotations

from agents.lang import load_program_text
from agents.lang.planning.control import Control, GoalView
from agents.lang.planning.syntax import ControlRule

from .test_syntax import TABLE_2
from .toy import TOY


def rules(text: str) -> tuple[ControlRule, ...]:
    program = load_program_text(TOY + text, "rules.tlp")
    return tuple(r for r in program.sections["control-rules"] if isinstance(r, ControlRule))


def view(priority: dict[str, int], compatible: set[str]) -> GoalView:
    low = min(priority.values())
    return GoalView(list(priority), lambda g: priority[g] == low, lambda g: g in compatible,
                    lambda g: f"{g} p{priority[g]}")


def test_table_2_selects_the_top_priority_and_the_compatible_goals():
    control = Control(rules(TABLE_2))
    chosen = control.select_goals(view({"g1": 1, "g2": 5, "g3": 5, "g4": 1}, {"g2"}))
    assert chosen == ["g1", "g2", "g4"]          # g3 waits
    assert control.firings == [
        f"select goal SELECT-TOP-PRIORITY-AND-COMPATIBLE-GOALS {g}"
        for g in ("g1 p1", "g2 p5", "g4 p1")]


def test_without_goal_rules_every_goal_is_selected_and_rejects_and_prefers_apply():
    assert not Control(()).selects_goals
    control = Control(rules("""
(control-rules
  (control-rule NOT-G2 (if (candidate-goal g2)) (then reject goal g2))
  (control-rule G3-FIRST (if (and (candidate-goal ?a) (candidate-goal g3)
                                  (ancestor-is-top-priority-goal ?a)))
    (then prefer goal g3 ?a)))"""))
    assert control.select_goals(view({"g1": 1, "g2": 5, "g3": 5}, set())) == ["g3", "g1"]
    assert control.firings == ["reject goal NOT-G2 g2 p5", "prefer goal G3-FIRST g3 p5 over "
                               "g1 p1"]


def test_a_select_rule_that_does_not_fire_leaves_the_choice_whole():
    """Seed 003, section 3: control rules "reduce the number of choices"; a select rule whose
    condition holds for no candidate selects nothing, and blocks nothing (every request
    waited, "not selected", for good)."""
    control = Control(rules("""
(control-rules
  (control-rule ONLY-G9 (if (candidate-goal g9)) (then select goal g9)))"""))
    assert control.select_goals(view({"g1": 1, "g2": 5}, set())) == ["g1", "g2"]
    assert control.firings == []
