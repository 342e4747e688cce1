"""Conjunctive goals (issue 22): ``(and L1 L2 ...)`` read wherever a goal is written, holding
when one binding makes every conjunct hold, decomposed by concept chaining in an order that
does not undo one conjunct for another (agents/lang/solving/ordering.py), shown as written, and
teaching skills for the conjuncts only (never one whose head is a conjunction)."""

from __future__ import annotations

import re

import pytest

from agents.lang import Engine, GoalError, GoalStatus, ProgramError, load_program_text
from agents.lang.reading.goals import parse_goal

from ..conftest import BLOCKS, figure3_program
from ..test_blocks import run

PROGRAM = figure3_program()


def _solve(goal: str, support: dict, cycles: int = 30):
    engine = Engine(PROGRAM)
    state = engine.add_goal(engine.remove_goal(engine.initial_state(), "p1"), goal, 1, "g1")
    return run(engine, state, support, cycles=cycles)


def _actions(trace) -> list[list]:
    return [a for _, acts in trace for a in acts]


def test_a_conjunction_is_read_and_checked_like_a_concepts_relations():
    goal = parse_goal("(and (on A B) (not (on B C)) (on ?x A) (< ?n 3) (ontable ?n T))",
                      PROGRAM)
    assert str(goal) == "(and (on A B) (not (on B C)) (on ?x A) (< ?n 3) (ontable ?n T))"
    for text, message in [
            ("(and)", "column 1: a conjunctive goal needs at least one conjunct"),
            ("(and (on A B) (and (on B C)))",
             "column 15: a conjunct cannot itself be a conjunction"),
            ("(and (on A B) (< ?y 2))",
             "column 15: variable ?y of test (< ?y 2) in (and (on A B) (< ?y 2)) is bound by no "
             "positive conjunct"),
            ("(and (on A B) (onn B C))", "undefined concept 'onn' (conjunct (onn B C))"),
            ("(and (on A))", "concept on takes 2 argument(s), got 1 (conjunct (on A))")]:
        with pytest.raises(GoalError, match=re.escape(message)):
            parse_goal(text, PROGRAM)


def test_a_program_may_list_a_conjunction_among_its_goals():
    text = BLOCKS.read_text() + "\n(goals\n  (and (on B A) (clear B)))\n"
    program = load_program_text(text, "conj.tlp")
    assert [str(g.literal) for g in program.goals] == ["(and (on B A) (clear B))"]
    with pytest.raises(ProgramError, match=r"conj.tlp:\d+:\d+: undefined concept 'onn'"):
        load_program_text(BLOCKS.read_text() + "\n(goals (and (onn B A)))\n", "conj.tlp")


def test_variables_are_existential_as_in_relations():
    trace, *_ = _solve("(and (on ?x A) (clear ?x))", {"A": "T", "B": "A", "C": "T"}, 1)
    assert trace[0][0].status_of("g1") is GoalStatus.SATISFIED   # B is on A and clear


def test_towers_are_built_from_their_base():
    """(and (on A B) (on B C)), all on the table, written top first: (on A B) would undo
    (clear B), which (on B C) needs to lift B; so (on B C) comes first."""
    trace, support, *_ = _solve("(and (on A B) (on B C))", {"A": "T", "B": "T", "C": "T"})
    assert _actions(trace) == [["*pickup", "B", "T"], ["*stack", "B", "C"],
                               ["*pickup", "A", "T"], ["*stack", "A", "B"]]
    assert support == {"A": "B", "B": "C", "C": "T"}


def test_the_sussman_anomaly_is_solved_in_the_fewest_actions():
    """C on A, A and B on the table. (on B C) first would cover C, which (on A B)'s plan must
    clear to free A; (on A B) first would be undone by (on B C). The part of (on A B)'s plan
    that (on B C) threatens, (clear A), comes first: six actions, the optimum."""
    trace, support, *_ = _solve("(and (on A B) (on B C))", {"A": "T", "C": "A", "B": "T"})
    assert _actions(trace) == [["*unstack", "C", "A"], ["*putdown", "C", "T"],
                               ["*pickup", "B", "T"], ["*stack", "B", "C"],
                               ["*pickup", "A", "T"], ["*stack", "A", "B"]]
    assert support == {"A": "B", "B": "C", "C": "T"}
    assert [d.goals[0].instance for d, _ in trace][:2] == ["(clear A)", "(on B C)"]


def test_a_conjunct_that_holds_may_be_undone_for_a_while_when_nothing_else_will_do():
    """(on C D) holds, but D stands on E, which must go on F: C is lifted off D for a while
    and put back (the Sussman anomaly's kind: undoing one conjunct to get another)."""
    trace, support, *_ = _solve("(and (on C D) (on E F))",
                                {"E": "T", "D": "E", "C": "D", "F": "T"})
    assert support == {"C": "D", "D": "T", "E": "F", "F": "T"}
    held = [d.status_of("g1") for d, _ in trace]
    assert held[-1] is GoalStatus.SATISFIED
    assert _actions(trace)[0] == ["*unstack", "C", "D"]


def test_the_goal_is_shown_as_written_with_the_conjunct_worked_on():
    trace, *_ = _solve("(and (on A B) (on B C))", {"A": "T", "B": "T", "C": "T"}, 3)
    report = trace[2][0].goals[0]
    assert report.goal == "(and (on A B) (on B C))" and report.instance == "(on B C)"
    assert "  1 g1       active    (and (on A B) (on B C))  [(on B C)]" in \
        trace[2][0].explain()
    assert trace[2][0].to_dict()["goals"][0]["goal"] == "(and (on A B) (on B C))"


def test_learning_from_a_conjunction_teaches_its_conjuncts_and_no_anonymous_head():
    *_, state = _solve("(and (on A B) (on B C))", {"A": "T", "C": "A", "B": "T"})
    heads = [t.split("\n")[1] for t in state.learned]
    assert heads and not any(h.startswith("((and") for h in heads)
    assert "((on ?b1 ?b2)" in heads
    again = Engine(PROGRAM)
    fresh = again.add_goal(again.remove_goal(again.initial_state(learned=state.learned), "p1"),
                           "(and (on D E) (on E F))", 1, "g1")
    trace, support, *_ = run(again, fresh, {"D": "T", "F": "D", "E": "T"}, cycles=30)
    assert support == {"D": "E", "E": "F", "F": "T"}
    assert not any(d.section("solver") and d.section("solver").solving for d, _ in trace)


def test_a_conjunction_that_cannot_hold_fails_after_its_first_circle_naming_it():
    """(and (on A B) (on B A)): each conjunct undoes the other. The agent lifts A, puts it back
    to lift B, and so on; the second time round it is back in a situation it was in (cycle 8)
    without progress: the loop watch (agents/lang/execution/loops.py) makes the solver give the
    conjunct
    up, and with it the goal, within one more circle of six cycles."""
    trace, *_ = _solve("(and (on A B) (on B A))", {"A": "T", "B": "T"}, 40)
    statuses = [d.status_of("g1") for d, _ in trace]
    first = statuses.index(GoalStatus.FAILED)
    assert first <= 20 and set(statuses[first:]) == {GoalStatus.FAILED}
    note = trace[-1][0].goals[0].note
    assert note.startswith("(and (on A B) (on B A)) cannot be achieved")
    assert note.startswith("(and (on A B) (on B A)) cannot be achieved without going round in "
                           "a circle (loop: back in the situation of cycle 8 while pursuing g1 "
                           "(and (on A B) (on B A)), with no progress since")
    assert all(acts == [] for _, acts in trace[first:])


def test_the_rogue_planner_refuses_a_conjunctive_request_saying_what_it_takes():
    from ..conftest import ROOT

    engine = Engine(load_program_text((ROOT / "programs" / "office_rogue.tlp").read_text(),
                                      "office_rogue.tlp"), solver="rogue")
    goal = "(and (delivered mail-mitchell r-5313) (delivered coffee-1 reid))"
    state = engine.add_goal(engine.initial_state(), goal, 5, "g1")
    report = engine.cycle(state, []).decision.goals[0]
    assert (report.status, report.note) == (GoalStatus.FAILED, f"{goal}: the planner takes a "
                                            "request for one literal; post each conjunct as a "
                                            "request of its own")
