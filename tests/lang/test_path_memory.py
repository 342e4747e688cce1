"""What the executive remembers of a goal's path, and when it lets go (seed 000, "Inference and
Execution Mechanisms": "When it encounters a skill instance on the path that is no longer
executable, the system finds another executable skill"; "Adding Goal Priorities": a suspended
goal is resumed after the higher one is re-achieved)."""

from __future__ import annotations

import pytest

from agents.lang import Engine, GoalError, GoalStatus, LangError, ProgramError, load_program_text
from agents.lang.execution.executive import Impasse, ImpasseHandler

from .conftest import me

PACKAGE = ["package", "PACKET1", "address", 4, "delivered", "NIL"]


def _run(engine, state, cycles):
    out = []
    for percepts in cycles:
        result = engine.cycle(state, percepts)
        out.append(result.decision)
        state = result.state
    return out, state


def _actions(d):
    return [a.to_list() for a in d.actions]


def test_a_broken_path_with_no_alternative_is_forgotten(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered PACKET1)", 5, "g1")
    d, state = _run(minidrive, state, [
        [me(position=0), PACKAGE],   # path: package-delivered#2 -> at-address#1
        [me(position=1)],            # the package is out of sight: the path breaks, impasse
        [me(position=6), PACKAGE]])  # back in sight, but already past the address
    assert d[1].status_of("g1") is GoalStatus.IMPASSE and state.path_of("g1") == ()
    # entered afresh, at-address#1's start (< 6 4) fails: no "continued" skill driving backwards
    assert d[2].status_of("g1") is GoalStatus.IMPASSE and _actions(d[2]) == []
    assert any(w.skill == "at-address#1" and w.reason == "start failed: (< 6 4)"
               for w in d[2].why)


def test_a_suspended_goal_resumes_only_if_every_start_holds_now(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered PACKET1)", 5, "g1")
    d, state = _run(minidrive, state, [
        [me(position=0), PACKAGE],
        [me(speed=30, position=2), PACKAGE],   # too fast: g1 suspended
        [me(position=6), PACKAGE]])            # the world moved on while it was suspended
    assert d[1].status_of("g1") is GoalStatus.SUSPENDED
    assert d[2].status_of("g1") is GoalStatus.IMPASSE and _actions(d[2]) == []
    assert any(w.skill == "at-address#1" and
               w.reason == "cannot resume the previous skill: start failed: (< 6 4)"
               for w in d[2].why)


def test_an_acting_goal_continues_without_rechecking_start(minidrive):
    state = minidrive.add_goal(minidrive.initial_state(), "(package-delivered PACKET1)", 5, "g1")
    d, _ = _run(minidrive, state, [[me(position=0), PACKAGE], [me(position=1), PACKAGE]])
    assert [(s.skill, s.mode) for s in d[1].path] == [
        ("package-delivered#2", "continued"), ("at-address#1", "continued")]


def test_goal_variables_that_no_percept_fixes_are_refused(blocks):
    with pytest.raises(GoalError, match=r"variable \?x cannot mean every instance: clause "
                                        r"unstackable#1 takes \?b from no percept"):
        blocks.add_goal(blocks.initial_state(), "(unstackable ?x A)")
    assert blocks.add_goal(blocks.initial_state(), "(ontable ?x T)")   # (block ?b ...) fixes it


def test_a_program_goal_with_such_a_variable_is_a_program_error():
    text = """
(concepts ((ready ?x) :percepts ((o ?x ready T)))
          ((both ?x ?y) :relations ((ready ?x) (ready ?y))))
(goals (both ?x ?y))"""
    with pytest.raises(ProgramError, match=r"goals.tlp:4:8: goal \(both \?x \?y\): variable \?x"):
        load_program_text(text, "goals.tlp")


class _GiveUp(ImpasseHandler):
    """An impasse handler that gives every goal up at once, to show what failing means."""

    def solve(self, finder, walk, entry, unsatisfied):
        return Impasse(failed=f"no way to achieve {unsatisfied[0]}")


def test_a_failed_goal_says_why_and_blocks_the_goals_after_it_until_withdrawn(minidrive):
    """Seed 000: "the agent considers a goal only when all more important goals are
    satisfied": a goal given up on still blocks the goals after it (issue 22); the goal-entry
    process withdraws a user's failed goal, and then they go on."""
    engine = Engine(minidrive.program, solver=_GiveUp())
    state = engine.add_goal(engine.initial_state(), "(package-delivered PACKET1)", 0, "g1")
    far_behind = ["package", "PACKET1", "address", -5, "delivered", "NIL"]
    d, state = _run(engine, state, [[me(speed=30), far_behind], [me(speed=30), far_behind]])
    for decision in d:
        report = decision.goals[0]
        assert (report.id, report.status) == ("g1", GoalStatus.FAILED)
        assert report.note == "no way to achieve (package-delivered PACKET1)"
        assert decision.status_of("p2") is GoalStatus.PENDING      # too fast, but waits
        assert [g.note for g in decision.goals if g.id == "p2"] == ["waits: g1 comes first"]
        assert _actions(decision) == []
    assert state.failure_of("g1") == "no way to achieve (package-delivered PACKET1)"
    d, state = _run(engine, engine.remove_goal(state, "g1"), [[me(speed=30), far_behind]])
    assert d[0].status_of("p2") is GoalStatus.ACTIVE and _actions(d[0]) == [["*brake", 20]]


def test_outcomes_of_the_last_cycle_are_read_and_checked(minidrive):
    state = minidrive.initial_state()
    ok = [{"action": ["*brake", 20], "status": "failed", "reason": "pedal stuck"}]
    assert minidrive.cycle(state, [me()], ok).decision is not None
    with pytest.raises(LangError, match="status: expected 'done' or 'failed', got 'maybe'"):
        minidrive.cycle(state, [me()], [{"action": ["*brake"], "status": "maybe"}])


def test_the_agents_random_draws_depend_only_on_seed_cycle_and_tag(minidrive):
    a = minidrive.initial_state(seed=7)
    assert a.rng("scs").random() == minidrive.initial_state(seed=7).rng("scs").random()
    assert a.rng("scs").random() != minidrive.initial_state(seed=8).rng("scs").random()
    assert a.rng("scs").random() != a.rng("other").random()
