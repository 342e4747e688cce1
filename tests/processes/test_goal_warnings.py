"""A goal whose instances include one that nothing can make true (issue 31): ``(on D ?x)``
means every instance, ``(on D D)`` among them; the goal-entry process accepts the post and
says so in its reply, pointing to ``(and ...)`` for "some instance"; a goal without such an
instance, or a conjunction, gets no warning."""

from __future__ import annotations

import logging
from pathlib import Path

from agents.processes.goal_warnings import engine_warner
from agents.processes.goals import GoalEntry, engine_validator, standing_goals
from bus.messages import Envelope, GoalRequest
from world.run_scenario import load_scenario

ROOT = Path(__file__).resolve().parents[2]
ENV = Envelope(1, "r", -1, "cli", 0)
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
"""


def _entry(tmp_path: Path) -> GoalEntry:
    path = tmp_path / "bw.toml"
    path.write_text(TOML.format(program=ROOT / "programs" / "blocks.tlp"))
    scenario = load_scenario(path)
    return GoalEntry(scenario, tmp_path / "goals.json", engine_validator(scenario),
                     logging.getLogger("test"), standing=standing_goals(scenario),
                     warn=engine_warner(scenario))


def _post(entry: GoalEntry, goal: str) -> tuple[bool, str]:
    ok, reason, _goals, _cycle = entry.answer(GoalRequest(ENV, "post", "ME", goal, 5, "",
                                                          False))
    return ok, reason


def test_a_post_whose_instances_include_an_impossible_one_is_warned(tmp_path):
    entry = _entry(tmp_path)
    ok, reason = _post(entry, "(on D ?x)")
    assert ok and reason.startswith("posted g1 for ME: (on D ?x) (from cycle 0); warning: ")
    assert "(on D ?x) means every instance, and its instances include (on D D), which no " \
           "skill or concept can make true" in reason
    assert reason.endswith("for some instance, write (and (on D ?x))")
    assert entry.store.get("g1").goal == "(on D ?x)"


def test_possible_instances_and_conjunctions_are_not_warned(tmp_path):
    entry = _entry(tmp_path)
    for goal in ["(clear ?b)", "(and (on D ?x))", "(on D A)", "(ontable ?b T)"]:
        ok, reason = _post(entry, goal)
        assert ok and "warning" not in reason, (goal, reason)


def test_the_goal_entry_looks_at_the_world_before_any_post(tmp_path):
    """The goal-entry process makes the start's world once, for every agent, before it
    announces itself (eager): its warnings are the lazy warner's, and one that cannot make
    the world warns of nothing, never fails a post."""
    path = tmp_path / "bw.toml"
    path.write_text(TOML.format(program=ROOT / "programs" / "blocks.tlp"))
    scenario = load_scenario(path)
    lazy, eager = engine_warner(scenario), engine_warner(scenario, eager=True)
    for goal in ["(on D ?x)", "(clear ?b)", "(on D A)"]:
        assert eager("ME", goal) == lazy("ME", goal), goal
    assert eager("ME", "(on D ?x)")
    assert eager("NOBODY", "(on D ?x)") == ""
    broken = tmp_path / "broken.toml"
    broken.write_text(TOML.format(program=ROOT / "programs" / "blocks.tlp")
                      .replace('[["C", "A"], ["B"], ["D"]]', '[["C", "A"], ["C"], ["D"]]'))
    assert engine_warner(load_scenario(broken), eager=True)("ME", "(on D ?x)") == ""
