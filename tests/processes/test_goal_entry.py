"""The goal-entry process's verdicts (issue 12, items 6 and 7): the priority rule, cancelling
an achieved goal, and the hint for a goal about an object no percept mentions."""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from agents.processes.goal_store import GoalState
from agents.processes.goal_texts import rank_problem
from agents.processes.goals import GoalEntry, engine_validator, standing_goals
from agents.processes.hints import absent, with_hints
from bus.messages import Envelope, GoalRequest
from world.run_scenario import load_scenario

ROOT = Path(__file__).resolve().parents[2]
DEMO = ROOT / "scenarios" / "driving_demo.toml"   # programs/driving.tlp: 2 standing laws
ENV = Envelope(1, "r", -1, "cli", 0)


@pytest.fixture
def entry(tmp_path) -> GoalEntry:
    scenario = load_scenario(DEMO)
    return GoalEntry(scenario, tmp_path / "goals.json", engine_validator(scenario),
                     logging.getLogger("test"), standing=standing_goals(scenario))


def ask(entry: GoalEntry, op: str, goal: str = "", priority: int = 0, goal_id: str = "",
        force: bool = False) -> tuple[bool, str]:
    ok, reason, _goals, _cycle = entry.answer(GoalRequest(ENV, op, "ME", goal, priority,
                                                          goal_id, force))
    return ok, reason


def test_the_rule_names_the_standing_goals_a_priority_would_outrank():
    laws = ("(not-hitting-pedestrians ME)", "(keeping-distance ME)", "(at-desired-speed ME)",
            "(in-right-lane ME)", "(at-cruising-speed ME)")
    assert rank_problem(laws, 5) == "" and rank_problem(laws, 100) == ""
    assert rank_problem(laws, 4).startswith(
        "priority 4 ranks the goal above the program's standing goal p5 (at-cruising-speed ME)")
    assert "p2 (keeping-distance ME), p3 (at-desired-speed ME), p4 (in-right-lane ME) and 1 " \
           "more" in rank_problem(laws, 1)
    assert rank_problem((), 1) == ""          # a program without goals: nothing to outrank


def test_a_post_above_the_driving_laws_is_refused_unless_forced(entry):
    ok, reason = ask(entry, "post", "(package-delivered PACKET2)", 1)
    assert not ok
    assert "above the program's standing goal p2 (at-desired-speed ?self)" in reason
    assert "give priority 2 or more" in reason and "--force" in reason
    assert entry.store.goals == ()
    ok, reason = ask(entry, "post", "(package-delivered PACKET2)", 1, force=True)
    assert ok and reason.startswith("posted g1 for ME: (package-delivered PACKET2)")
    assert "forced: priority 1 ranks the goal above" in reason
    assert entry.store.get("g1").priority == 1
    assert ask(entry, "post", "(package-delivered PACKET1)", 2)[0]     # after both laws


def test_raising_a_goal_above_the_laws_is_refused_unless_forced(entry):
    assert ask(entry, "post", "(package-delivered PACKET2)", 100)[0]
    ok, reason = ask(entry, "priority", priority=1, goal_id="g1")
    assert not ok and "p2 (at-desired-speed ?self)" in reason
    assert entry.store.get("g1").priority == 100
    assert ask(entry, "priority", priority=5, goal_id="g1") == (
        True, "g1 now has priority 5 (from cycle 0)")
    assert ask(entry, "priority", priority=1, goal_id="g1", force=True)[0]


def test_cancelling_an_achieved_goal_is_refused_like_a_cancelled_one(entry):
    assert ask(entry, "post", "(package-delivered PACKET1)", 5)[0]
    entry.store = entry.store.update_from_intention(
        "ME", {"goals": [{"id": "g1", "status": "satisfied"}]}, 213)
    assert entry.store.get("g1").status is GoalState.ACHIEVED
    ok, reason = ask(entry, "cancel", goal_id="g1")
    assert not ok and reason == ("g1: already achieved (cycle 213); an achieved goal stays "
                                 "achieved (force the cancel to stop the agent keeping it)")
    assert entry.store.get("g1").status is GoalState.ACHIEVED
    assert ask(entry, "cancel", goal_id="g1", force=True)[0]      # withdrawn all the same
    assert entry.store.get("g1").status is GoalState.CANCELLED
    assert entry.store.get("g1").note == "achieved at cycle 213, then withdrawn"
    assert ask(entry, "post", "(package-delivered PACKET2)", 5)[0]
    assert ask(entry, "cancel", goal_id="g2")[0]
    assert ask(entry, "cancel", goal_id="g2") == (False, "g2: already cancelled")


def test_a_goal_naming_an_object_no_percept_mentions_gets_a_hint():
    percepts = [["self", "ME", "speed", 3.0], ["package", "PACKET1", "address", 6]]
    assert absent("(package-delivered PACKET9)", percepts) == ["PACKET9"]
    assert absent("(package-delivered PACKET1)", percepts) == []
    assert absent("(on ?x 3)", percepts) == []            # variables and numbers are no names
    decision = {"goals": [
        {"id": "g1", "goal": "(package-delivered PACKET9)", "status": "pending",
         "note": "no path with free resources"},
        {"id": "g2", "goal": "(package-delivered PACKET8)", "status": "satisfied", "note": ""},
        {"id": "g3", "goal": "(package-delivered PACKET7)", "status": "failed", "note": ""}]}
    notes = [g["note"] for g in with_hints(decision, percepts)["goals"]]
    assert notes == ["no path with free resources; no percept mentions PACKET9: is there such "
                     "an object?", "", "no percept mentions PACKET7: is there such an object?"]


def test_the_store_mirrors_a_pending_goals_note_so_goal_list_shows_the_hint(entry):
    assert ask(entry, "post", "(package-delivered PACKET9)", 5)[0]
    hint = "no percept mentions PACKET9: is there such an object?"
    entry.store = entry.store.update_from_intention(
        "ME", {"goals": [{"id": "g1", "status": "pending", "note": hint}]}, 3)
    assert entry.store.get("g1").note == hint
    listed = entry.answer(GoalRequest(ENV, "list", "ME"))[2]
    assert listed[0]["note"] == hint


def test_a_goal_that_does_not_read_is_refused_naming_it_once_and_its_column(entry):
    # trial 2026-12-02 #15: "refused: (cruising ME: refused for ME: goal '(cruising ME':
    # 1:1: '(' is never closed" echoed the goal twice, with a position as in a file
    ok, reason = ask(entry, "post", "(cruising ME", 5)
    assert not ok
    assert reason == "ME cannot take goal '(cruising ME': column 1: '(' is never closed " \
                     "(missing ')')"
    ok, reason = ask(entry, "post", "(flying ME)", 5)
    assert reason == "ME cannot take goal (flying ME): undefined concept 'flying'"
    ok, reason = ask(entry, "post", "(package-delivered PACKET1 (x)", 5)
    assert reason.count("(package-delivered PACKET1 (x)") == 1 and "column 1:" in reason


@pytest.mark.parametrize("op", ["cancel", "priority"])
def test_a_program_goal_cannot_be_cancelled_or_reprioritised_and_says_so(entry, op):
    # trial 2026-12-02 #16: `teleo goal cancel p1` said "no goal 'p1'"
    ok, reason = ask(entry, op, priority=7, goal_id="p1")
    what = "cancelled" if op == "cancel" else "given another priority"
    assert not ok and reason.startswith(
        f"p1 is a program goal of ME, (not-hitting-pedestrians ?self): it cannot be {what}")
    ok, reason = ask(entry, op, priority=7, goal_id="p2")
    assert not ok and reason.startswith("p2 is a program goal of ME, (at-desired-speed ?self)")
    ok, reason = ask(entry, op, priority=7, goal_id="p3")   # driving.tlp has two
    assert not ok and reason == "no goal 'p3': the program goals of ME are p1..p2"
    assert ask(entry, "post", "(package-delivered PACKET1)", 5)[0]
    assert ask(entry, op, priority=7, goal_id="g1")[0]      # a user goal still can


def test_a_refused_scripted_request_is_kept_for_the_summary(tmp_path):
    """Issue 31 (N13): a launch's refused scripted request was only a line in goals.log; the
    goal store keeps it (goals.json "refused"), and the launch's summary reads it there."""
    from tools.records.summary import _goals

    text = DEMO.read_text().replace('"programs/driving.tlp"', f'"{ROOT}/programs/driving.tlp"')
    path = tmp_path / "s.toml"
    path.write_text(text + '[[goals]]\nop = "cancel"\ngoal_id = "g1"\nat_cycle = 2\n'
                           '[[goals]]\nop = "cancel"\ngoal_id = "g1"\nat_cycle = 3\n')
    scenario = load_scenario(path)
    entry = GoalEntry(scenario, tmp_path / "goals.json", engine_validator(scenario),
                      logging.getLogger("test"), standing=standing_goals(scenario))
    for cycle in range(5):
        entry.cycle = cycle
        entry._scripted(cycle)
    expected = ["scripted cancel of g1 at cycle 3 refused: g1: already cancelled"]
    assert list(entry.store.refused) == expected
    assert _goals(tmp_path / "goals.json")[2] == expected


def test_the_requests_scripted_for_one_cycle_are_saved_together_before_its_lists(
        tmp_path, monkeypatch):
    """The scenario's requests due at a cycle (here three posts and a refused cancel) are
    applied and then saved once, durably, before that cycle's goal lists are made: a
    restarted goal entry finds them all, marked done, and does not apply them again."""
    from agents.processes import goal_file

    text = DEMO.read_text().replace('"programs/driving.tlp"', f'"{ROOT}/programs/driving.tlp"')
    path = tmp_path / "s.toml"
    path.write_text(text + "".join(
        f'[[goals]]\nop = "post"\nagent = "ME"\ngoal = "(package-delivered PACKET{k})"\n'
        f"priority = 5\nat_cycle = 4\n" for k in (7, 8, 9))
        + '[[goals]]\nop = "cancel"\ngoal_id = "g9"\nat_cycle = 4\n')
    scenario = load_scenario(path)
    store = tmp_path / "goals.json"
    entry = GoalEntry(scenario, store, engine_validator(scenario), logging.getLogger("test"),
                      standing=standing_goals(scenario))
    saves = []
    real_save = goal_file.save
    monkeypatch.setattr(goal_file, "save", lambda s, p: saves.append(p) or real_save(s, p))
    entry.cycle = 4
    entry._scripted(4)
    assert len(saves) == 1 and not entry.unsaved
    again = goal_file.open_store(store).store
    assert again == entry.store
    assert [g.goal for g in again.goals] == [   # the demo's own of cycle 0, then these
        f"(package-delivered PACKET{k})" for k in (1, 7, 8, 9)]
    due = {i for i, g in enumerate(scenario.goals) if g.at_cycle <= 4}
    assert again.scripted_done == frozenset(due) and len(due) == len(scenario.goals) - 1
    assert again.refused[-1].startswith("scripted cancel of g9 at cycle 4 refused: ")
    restarted = GoalEntry(scenario, store, engine_validator(scenario),
                          logging.getLogger("test"), standing=standing_goals(scenario))
    restarted.cycle = 5
    restarted._scripted(5)
    assert restarted.store == again


def test_a_goal_whose_concept_needs_a_percept_that_is_not_there_says_which():
    """Issue 31 (N16): `(at-address ME 12 A)` failed with `no primitive skill achieves
    at-address`, though the program has at-address skills: no package has address 12 on A.
    Given the program, the note names the percept the concept needs; a goal about an object
    no percept mentions keeps its one hint."""
    from agents.lang import load_program

    program = load_program(str(ROOT / "programs" / "driving.tlp"))
    percepts = [["self", "ME", "speed", 0.0, "limit", 15.0, "street", "A"],
                ["package", "PACKET1", "address", 6, "street", "B", "dist", 40.0,
                 "angle", 10.0, "delivered", "NIL"]]
    reason = "no primitive skill achieves at-address"
    decision = {"goals": [
        {"id": "g1", "goal": "(at-address ME 12 A)", "status": "failed", "note": reason},
        {"id": "g2", "goal": "(at-address ME 6 B)", "status": "failed", "note": reason},
        {"id": "g3", "goal": "(package-delivered PACKET9)", "status": "failed", "note": ""}]}
    notes = [g["note"] for g in with_hints(decision, percepts, program)["goals"]]
    assert notes == [
        f"{reason}; no percept matches (package ?p address 12 street A) (at-address needs it)",
        reason,    # PACKET1 is there: its concept can hold
        "no percept mentions PACKET9: is there such an object?"]
    assert with_hints(decision, percepts)["goals"][0]["note"] == reason   # no program
