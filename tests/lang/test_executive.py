"""The executive: prioritized goals, suspension and resumption, preferred previous paths, goal
instances, run-time goals, explanations and state that round-trips (seed 000)."""

from __future__ import annotations

import json

import pytest

from agents.lang import Action, EngineState, GoalError, GoalStatus

from .conftest import me

PACKAGE = ["package", "PACKET1", "address", 4, "delivered", "NIL"]
MAN_AHEAD = ["man", "M31", "angle", 5.0, "dist", 12.0]


def statuses(decision):
    return {g.id: g.status for g in decision.goals}


def run(engine, state, cycles):
    """Run cycles from lists of percepts; return the decisions and the final state."""
    out = []
    for percepts in cycles:
        result = engine.cycle(state, percepts)
        out.append(result.decision)
        state = result.state
    return out, state


def test_program_goals_are_ordered_and_all_satisfied(minidrive):
    state = minidrive.initial_state()
    assert [(g.id, g.priority, g.text) for g in state.goals] == [
        ("p1", 1, "(not-hitting-pedestrians ME)"), ("p2", 2, "(at-desired-speed ?any)"),
        ("p3", 3, "(aligned ME)")]
    decision = minidrive.cycle(state, [me()]).decision
    assert set(statuses(decision).values()) == {GoalStatus.SATISFIED}
    assert decision.actions == () and decision.path == ()


def test_first_unsatisfied_goal_acts_alone(minidrive):
    decision = minidrive.cycle(minidrive.initial_state(),
                               [me(speed=30, heading=10.0), MAN_AHEAD]).decision
    assert statuses(decision) == {"p1": GoalStatus.ACTIVE, "p2": GoalStatus.PENDING,
                                  "p3": GoalStatus.PENDING}
    assert [a.to_list() for a in decision.actions] == [["*brake", 100]]
    assert decision.goals[1].note == "waits: p1 comes first"


def test_goal_with_variable_means_every_instance(minidrive):
    other = ["self", "YOU", "speed", 40.0, "limit", 25, "heading", 0.0, "position", 9]
    decision = minidrive.cycle(minidrive.initial_state(), [me(), other]).decision
    report = decision.goals[1]
    assert report.status is GoalStatus.ACTIVE
    assert report.instance == "(at-desired-speed YOU)" and dict(report.bindings) == {"any": "YOU"}
    assert decision.path[0].goal == "(at-desired-speed YOU)"
    # no percepts of the kind at all: the goal holds vacuously
    assert minidrive.cycle(minidrive.initial_state(), []).decision.goals[1].status \
        is GoalStatus.SATISFIED


def test_a_goal_with_a_variable_is_about_every_object_of_the_kind_not_only_those_it_holds_for(
        minidrive):
    # seed 000: "(at-desired-speed ?any) means it wants every vehicle to obey the speed
    # limit". package-delivered reads (package ?p delivered T): the constant says whether the
    # goal holds for a package, not which packages the goal is about.
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered ?any)",
                               priority=5, goal_id="g1")
    done = ["package", "PACKET2", "address", 4, "delivered", "T"]
    decision = minidrive.cycle(state, [me(position=0), done, PACKAGE]).decision
    report = decision.goals[-1]
    assert (report.status, report.instance) == (GoalStatus.ACTIVE, "(package-delivered PACKET1)")
    assert [a.to_list() for a in decision.actions] == [["*forward", 2]]
    both = [me(position=0), done, [*PACKAGE[:-1], "T"]]
    assert minidrive.cycle(state, both).decision.status_of("g1") is GoalStatus.SATISFIED


def test_violated_higher_goal_suspends_and_the_lower_goal_resumes_its_path(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered PACKET1)",
                               priority=5, goal_id="g1")
    d, state = run(minidrive, state, [
        [me(position=0), PACKAGE],            # deliver: drive towards the address
        [me(speed=30, position=2), PACKAGE],  # too fast: speed law first
        [me(position=2), PACKAGE],            # resume
        [me(position=4), PACKAGE],            # arrived: deliver
        [me(position=4), [*PACKAGE[:-1], "T"]]])
    assert [[a.to_list() for a in x.actions] for x in d] == [
        [["*forward", 2]], [["*brake", 20]], [["*forward", 2]], [["*deliver", "PACKET1"]], []]
    assert [x.status_of("g1") for x in d] == [
        GoalStatus.ACTIVE, GoalStatus.SUSPENDED, GoalStatus.ACTIVE, GoalStatus.ACTIVE,
        GoalStatus.SATISFIED]
    assert [(s.skill, s.mode) for s in d[0].path] == [
        ("package-delivered#2", "entered"), ("at-address#1", "entered")]
    # back from the suspension: every skill on the path could be started now, so it resumes
    assert [(s.skill, s.mode) for s in d[2].path] == [
        ("package-delivered#2", "resumed"), ("at-address#1", "resumed")]
    # only the broken part is replaced: the top skill continues, a new primitive is entered
    assert [(s.skill, s.mode) for s in d[3].path] == [
        ("package-delivered#2", "continued"), ("package-delivered#1", "entered")]
    assert state.path_of("g1") == ()


def test_user_goal_priority_ranks_after_equal_priorities(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(aligned YOU)", priority=1)
    state = minidrive.add_goal(state, "(at-desired-speed ME)", priority=0, goal_id="urgent")
    order = [g.id for g in sorted(state.goals, key=lambda g: (g.priority, g.seq))]
    assert order == ["urgent", "p1", "g4", "p2", "p3"]
    state = minidrive.set_priority(state, "urgent", 2)
    order = [g.id for g in sorted(state.goals, key=lambda g: (g.priority, g.seq))]
    assert order == ["p1", "g4", "p2", "urgent", "p3"]
    decision = minidrive.cycle(state, [me()]).decision
    assert [g.id for g in decision.goals] == order
    state = minidrive.remove_goal(state, "g4")
    assert [g.id for g in state.goals] == ["p1", "p2", "p3", "urgent"]


@pytest.mark.parametrize("goal, message", [
    ("(flying ME)", "undefined concept 'flying'"),
    ("(aligned ME YOU)", r"concept aligned takes 1 argument\(s\), got 2"),
    ("aligned", "expected one list"),
    ("(aligned ME", "never closed"),
])
def test_bad_goals_are_rejected(minidrive, goal, message):
    with pytest.raises(GoalError, match=message):
        minidrive.add_goal(minidrive.initial_state(), goal)


def test_unknown_goal_id_and_duplicate_id(minidrive):
    state = minidrive.initial_state()
    with pytest.raises(GoalError, match="no goal with id 'nope'"):
        minidrive.remove_goal(state, "nope")
    with pytest.raises(GoalError, match="already in use"):
        minidrive.add_goal(state, "(aligned ME)", goal_id="p1")


def test_impasse_explains_every_alternative_and_blocks_lower_goals(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered PACKET1)", 0)
    far_behind = ["package", "PACKET1", "address", -5, "delivered", "NIL"]
    decision = minidrive.cycle(state, [me(speed=30), far_behind]).decision
    assert decision.goals[0].status is GoalStatus.IMPASSE
    assert decision.status_of("p2") is GoalStatus.PENDING and decision.actions == ()
    reasons = [(w.depth, w.goal, w.skill, w.reason) for w in decision.why]
    assert reasons == [
        (0, "(package-delivered PACKET1)", "package-delivered#1",
         "start failed: (at-address ME -5)"),
        (1, "(at-address ME -5)", "at-address#1", "start failed: (< 0 -5)"),
        (0, "(package-delivered PACKET1)", "package-delivered#2",
         "subgoal (at-address ME -5) has no executable path")]


def test_missing_skill_is_reported(minidrive):
    program = minidrive.program
    assert program.skills_for("too-fast") == ()
    state = minidrive.add_goal(minidrive.initial_state(), "(too-fast ME)", 0)
    decision = minidrive.cycle(state, [me()]).decision
    assert [w.reason for w in decision.why] == ["no skill achieves too-fast"]


def test_actions_evaluate_arithmetic_at_execution_time(minidrive):
    decision = minidrive.cycle(minidrive.initial_state(), [me(speed=5.0, heading=-7.5)]).decision
    assert decision.actions == (Action("*gas", (5.0,)),)
    decision = minidrive.cycle(minidrive.initial_state(), [me(heading=-7.5)]).decision
    assert decision.actions == (Action("*steer", (7.5,)),)


def test_decision_and_state_are_plain_data_that_round_trip(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered PACKET1)", 5, "g1")
    result = minidrive.cycle(state, [me(), PACKAGE])
    d = result.decision.to_dict()
    assert json.loads(json.dumps(d)) == d
    assert d["goals"][3] == {"id": "g1", "goal": "(package-delivered PACKET1)", "priority": 5,
                             "status": "active", "bindings": {},
                             "instance": "(package-delivered PACKET1)", "note": ""}
    assert d["actions"] == [["*forward", 2]] and d["path"][1]["skill"] == "at-address#1"
    assert _plain(d)
    restored = EngineState.from_dict(json.loads(json.dumps(result.state.to_dict())))
    assert restored == result.state
    # a restarted process continues exactly as the original would
    nxt = [me(position=2), PACKAGE]
    assert minidrive.cycle(restored, nxt).decision == minidrive.cycle(result.state, nxt).decision


def _plain(x) -> bool:
    if isinstance(x, dict):
        return all(type(k) is str and _plain(v) for k, v in x.items())
    if isinstance(x, list):
        return all(_plain(v) for v in x)
    return type(x) in (str, int, float)


def test_bad_state_dicts_are_rejected_with_the_reason(minidrive):
    from agents.lang import StateError
    good = minidrive.initial_state().to_dict()
    with pytest.raises(StateError, match="version 7, expected 2"):
        EngineState.from_dict({**good, "version": 7})
    with pytest.raises(StateError, match="bad shape"):
        EngineState.from_dict({**good, "goals": [{"id": "p1"}]})
    with pytest.raises(GoalError, match="no goal with id 'zz'"):
        minidrive.set_priority(minidrive.initial_state(), "zz", 1)


def test_remembered_path_of_a_changed_program_is_ignored(blocks):
    from dataclasses import replace

    from agents.lang import StoredStep

    from .test_blocks import percepts
    stale = (StoredStep("(clear A)", 0, "no-such-skill#1", (("b", "A"),)),
             StoredStep("(clear B)", 999, "clear#1", ()))
    state = replace(blocks.initial_state(), paths=(("p1", stale),))
    decision = blocks.cycle(state, percepts({"A": "T", "B": "A"})).decision
    assert [(s.skill, s.mode) for s in decision.path] == [("clear#1", "entered")]
    assert decision.actions[0].to_list() == ["*unstack", "B", "A"]
