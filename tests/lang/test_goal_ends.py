"""Goals that end (issue 34, item 2): a goal posted `once` is dropped from pursuit when it is
achieved, not kept as a maintenance goal; a goal with a deadline fails with its reason when
it is not achieved in time. The engine counts its own cycles (pure: no clock)."""

from __future__ import annotations

import pytest

from agents.lang import EngineState, GoalError, GoalStatus

from .test_blocks import TOWER, primitive, run  # noqa: F401  (the fixture)


def _clear_a(engine, **ends):
    state = engine.remove_goal(engine.initial_state(), "p1")
    return engine.add_goal(state, "(clear A)", goal_id="g1", **ends)


def test_a_once_goal_is_not_kept_after_it_is_achieved(primitive):  # noqa: F811
    kept = run(primitive, _clear_a(primitive), TOWER, cycles=8)
    once = run(primitive, _clear_a(primitive, once=True), TOWER, cycles=8)
    assert [a for _, a in once[0]] == [a for _, a in kept[0]]   # achieved the same way
    done = [d.goals[0] for d, _ in once[0] if d.goals[0].status is GoalStatus.SATISFIED]
    assert done and done[-1].note.startswith("achieved at cycle ") and \
        done[-1].note.endswith("; once: not kept")
    # B put back on A: the kept goal is pursued again, the once goal is over
    again = run(primitive, kept[3], {**TOWER, "C": "T"}, cycles=3)
    assert [a for _, a in again[0]][0] == [["*unstack", "B", "A"]]
    over = run(primitive, once[3], {**TOWER, "C": "T"}, cycles=3)
    assert [a for _, a in over[0]] == [[], [], []]
    assert all(d.goals[0].status is GoalStatus.SATISFIED for d, _ in over[0])


def test_a_goal_not_achieved_by_its_deadline_fails_with_the_reason(primitive):  # noqa: F811
    state = primitive.remove_goal(primitive.initial_state(), "p1")
    state = primitive.add_goal(state, "(on A C)", goal_id="g1", deadline=2)
    trace, _, _, end = run(primitive, state, TOWER, cycles=5)
    statuses = [d.goals[0].status for d, _ in trace]
    assert GoalStatus.FAILED not in statuses[:2] and statuses[2:] == [GoalStatus.FAILED] * 3
    assert trace[2][0].goals[0].note == "(on A C) not achieved by cycle 2, its deadline"
    assert [a for _, a in trace[2:]] == [[], [], []]   # no longer pursued
    met = primitive.add_goal(primitive.remove_goal(primitive.initial_state(), "p1"),
                             "(clear A)", goal_id="g1", deadline=20)
    assert run(primitive, met, TOWER, cycles=8)[0][-1][0].goals[0].status \
        is GoalStatus.SATISFIED
    back = EngineState.from_dict(end.to_dict())       # a restarted executive keeps it over
    assert back.goals == end.goals and back.goals[0].ended.endswith("its deadline")


def test_a_state_without_them_is_written_as_before_and_bad_deadlines_are_refused(primitive):  # noqa: F811
    plain = primitive.initial_state().to_dict()["goals"][0]
    assert set(plain) == {"id", "goal", "priority", "seq", "origin"}
    for bad in (0, -3, 1.5, "5"):
        with pytest.raises(GoalError, match="deadline must be a whole number of cycles"):
            primitive.add_goal(primitive.initial_state(), "(clear A)", deadline=bad)
