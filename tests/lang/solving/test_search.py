"""Means-ends search (agents/lang/solving/search.py): on a toy task first, then in the Blocks
World: backtracking to the next alternative when a chain cannot succeed (a loop, a start that
cannot be achieved, a depth bound), and failure, with the reason, when none is left."""

from __future__ import annotations

import pytest

from agents.lang import Engine, GoalStatus, load_program_text
from agents.lang.solving.search import MAX_STACK

from ..test_blocks import run


def _deep(n: int) -> Engine:
    """A toy program: (p0 ?x) is (p1 ?x), ..., (p<n> ?x) is (ready ?x), a percept no skill
    changes: concept chaining goes down one level a cycle."""
    concepts = [f"((p{i} ?x) :percepts ((thing ?x)) :relations ((p{i + 1} ?x)))"
                for i in range(n)]
    text = f"""(concepts ((ready ?x) :percepts ((thing ?x ready yes)))
                          ((p{n} ?x) :percepts ((thing ?x)) :relations ((ready ?x)))
                          {' '.join(concepts)})"""
    return Engine(load_program_text(text, "deep.tlp"))


def _solve(engine: Engine, goal: str, percepts: list, cycles: int):
    state = engine.add_goal(engine.initial_state(), goal, goal_id="g1")
    out = []
    for _ in range(cycles):
        result = engine.cycle(state, percepts)
        out.append(result.decision)
        state = result.state
    return out, state


def test_toy_task_one_push_per_cycle_then_nothing_to_chain_off():
    decisions, state = _solve(_deep(3), "(p0 A)", [["thing", "A", "ready", "no"]], 6)
    assert [d.section("solver").stack("g1") for d in decisions[:5]] == [
        ["(p0 A)", "(p1 A)"], ["(p0 A)", "(p1 A)", "(p2 A)"],
        ["(p0 A)", "(p1 A)", "(p2 A)", "(p3 A)"],
        ["(p0 A)", "(p1 A)", "(p2 A)", "(p3 A)", "(ready A)"],
        []]   # nothing achieves (ready A): every level fails in turn, the goal too
    assert [d.status_of("g1") for d in decisions] == [GoalStatus.IMPASSE] * 4 + \
        [GoalStatus.FAILED] * 2
    events = decisions[4].section("solver").events
    assert events[0] == ("g1: backtracked: (ready A) cannot be achieved: nothing to chain off: "
                         "no primitive skill achieves ready; ready is a primitive concept, "
                         "with no subconcepts to decompose into")
    assert events[-1] == f"g1: failed: {state.failure_of('g1')}"
    assert state.failure_of("g1").startswith(
        "(p0 A) cannot be achieved: every alternative failed (concept p0#1: its subgoal (p1 A) "
        "cannot be achieved: every alternative failed (concept p1#1: its subgoal (p2 A)")
    assert state.solver.stacks == ()


def test_toy_task_depth_bound():
    decisions, state = _solve(_deep(MAX_STACK + 5), "(p0 A)", [["thing", "A", "ready", "no"]],
                              MAX_STACK + 2)
    assert len(decisions[MAX_STACK - 2].section("solver").stack("g1")) == MAX_STACK
    failed = [d for d in decisions if d.status_of("g1") is GoalStatus.FAILED]
    assert failed and f"depth bound: the goal stack already holds {MAX_STACK} (sub)goals" in \
        "\n".join(failed[0].section("solver").events)


@pytest.fixture(scope="module")
def blocks():

    from ..conftest import figure3_program
    return Engine(figure3_program())


def _goal(engine, goal):
    return engine.add_goal(engine.remove_goal(engine.initial_state(), "p1"), goal, goal_id="g1")


FALLBACK = """
(concepts ((armed ?x) :percepts ((thing ?x armed yes)))
          ((ready ?x) :percepts ((thing ?x ready yes)))
          ((lit ?x) :percepts ((thing ?x lit yes)))
          ((done ?x) :percepts ((thing ?x done yes))))
(skills ((done ?x) :percepts ((thing ?x)) :start ((armed ?x)) :actions ((*fire ?x)))
        ((done ?x) :percepts ((thing ?x)) :start ((lit ?x)) :actions ((*finish ?x)))
        ((lit ?x) :percepts ((thing ?x)) :start ((ready ?x)) :actions ((*light ?x))))
"""


# a skill for a concept defined by relations: the program admits no relaxed estimate
# (agents/lang/solving/relaxed.py), so the primitive skills are tried in program order
NO_ESTIMATE = FALLBACK + """
(concepts ((set ?x) :percepts ((thing ?x)) :relations ((lit ?x))))
(skills ((set ?x) :percepts ((thing ?x)) :start ((ready ?x)) :actions ((*set ?x))))
"""


def test_backtrack_the_first_chain_fails_the_second_succeeds():
    """(done A): skill chaining tries the first skill (program order), pushing its start
    (armed A); nothing achieves it, so the search backtracks to the second skill, whose start
    (lit A) has an executable path, and executes it in the same cycle."""
    decisions, state = _solve(Engine(load_program_text(NO_ESTIMATE, "fallback.tlp")),
                              "(done A)", [["thing", "A", "ready", "yes"]], 2)
    stacks = [d.section("solver").stack("g1") for d in decisions]
    assert stacks == [["(done A)", "(armed A)"], ["(done A)", "(lit A)"]]
    assert decisions[1].section("solver").events == (
        "g1: backtracked: (armed A) cannot be achieved: nothing to chain off: no primitive "
        "skill achieves armed; armed is a primitive concept, with no subconcepts to decompose "
        "into",
        "g1: pushed (lit A): chained off skill (finish A) because its start (lit A) is false",
        "g1: executing (lit A) by lit#1")
    assert [a.to_list() for a in decisions[1].actions] == [["*light", "A"]]
    entry = decisions[1].section("solver").to_dict()["stacks"][0]["entries"][0]
    assert entry["decision"]["alternative"] == 2 and entry["failures"][0].startswith(
        "(fire A): its subgoal (armed A) cannot be achieved")


def test_with_the_relaxed_estimate_the_skill_whose_start_can_hold_is_chained_first():
    """The same program without the concept admits the relaxed estimate: the primitive skills
    for a goal are ranked by it across skills, not only bindings within one (logistics: a
    package to an airport is unloaded from the airplane that can bring it, not from a truck
    of the airport's city that could only be loaded there), so (armed A), which nothing
    achieves, is never pushed."""
    decisions, _ = _solve(Engine(load_program_text(FALLBACK, "fallback.tlp")), "(done A)",
                          [["thing", "A", "ready", "yes"]], 1)
    assert decisions[0].section("solver").stack("g1") == ["(done A)", "(lit A)"]


def test_a_way_reachable_only_through_its_own_goal_is_not_chained_off(blocks):
    """(holding A) with C on A on B: (pickup A T) comes first in program order, but its start
    needs (ontable A T), and every way to that passes through (holding A) itself (put A
    down): a landmark of it (agents/lang/solving/landmarks.py). The search leaves that way
    out and chains off (unstack A B) at once, instead of discovering the loop three pushes
    later."""
    trace, support, holding, state = run(blocks, _goal(blocks, "(holding A)"),
                                         {"B": "T", "A": "B", "C": "A"}, cycles=6)
    assert [d.section("solver").stack("g1") for d, _ in trace[:1]] == [
        ["(holding A)", "(unstackable A B)"]]
    first = trace[0][0].section("solver").to_dict()["stacks"][0]["entries"][0]
    assert first["decision"]["of"] == 1 and first["decision"]["shows"] == "(unstack A B)"
    assert [a for _, acts in trace for a in acts] == [
        ["*unstack", "C", "A"], ["*putdown", "C", "T"], ["*unstack", "A", "B"]]
    assert holding == "A" and trace[-1][0].status_of("g1") is GoalStatus.SATISFIED


def test_an_impossible_problem_ends_failed_with_the_reason(blocks):
    """(on A A): (stackable A A) needs (clear A) and (holding A), and (clear A) is defined
    with (not (holding A)): the two contradict one another, so the concept is not decomposed
    (issue 31: no chasing an instance nothing can make true), and the goal fails at once,
    without an action, saying why."""
    trace, *_, state = run(blocks, _goal(blocks, "(on A A)"), {"A": "T", "B": "A"}, cycles=12)
    statuses = [d.status_of("g1") for d, _ in trace]
    assert GoalStatus.FAILED in statuses
    first = statuses.index(GoalStatus.FAILED)
    assert set(statuses[first:]) == {GoalStatus.FAILED}
    assert state.failure_of("g1") == (
        "(on A A) cannot be achieved: every alternative failed ((stack A A): its subgoal "
        "(stackable A A) cannot be achieved: nothing to chain off: no primitive skill achieves "
        "stackable; its definition cannot be decomposed here; left out concept stackable#1 "
        "(stackable A A): (clear A) (holding A) contradict one another)")
    assert first <= 1 and all(acts == [] for _, acts in trace)
    assert trace[first][0].goals[0].note == state.failure_of("g1")
    assert state.solver.stacks == () and all(acts == [] for _, acts in trace[first:])


def test_a_failed_goal_blocks_the_goals_after_it_until_withdrawn(blocks):
    """An unknown block: nothing to chain off; the failed goal blocks the program's goal
    (clear A) (issue 22) until it is withdrawn, as the goal-entry process withdraws a user's
    failed goal; then (clear A) is solved."""
    state = blocks.add_goal(blocks.initial_state(), "(clear Q)", priority=0, goal_id="g1")
    trace, *_, state = run(blocks, state, {"A": "T", "B": "A", "C": "B"}, cycles=2)
    for decision, actions in trace:
        assert decision.status_of("g1") is GoalStatus.FAILED and actions == []
        assert decision.goals[0].note == (
            "(clear Q) cannot be achieved: nothing to chain off: no primitive skill for clear "
            "applies here (its :percepts do not match, or its start could not become subgoals);"
            " its definition cannot be decomposed here")
        assert decision.status_of("p1") is GoalStatus.PENDING
    trace, *_ = run(blocks, blocks.remove_goal(state, "g1"), {"A": "T", "B": "A", "C": "B"},
                    cycles=1)
    decision = trace[0][0]
    assert decision.status_of("p1") is GoalStatus.IMPASSE
    assert decision.section("solver").stack("p1") == ["(clear A)", "(unstackable B A)"]


def test_a_way_whose_test_reads_a_variable_nothing_bound_is_no_way_and_no_crash():
    """bench/faults/fuzz.py (executive, 2026-12-02): a concept's :tests read ?d, which only its
    relation (near ?x ?d) binds; with no (near A ...) belief the solver's candidate binding
    left ?d open and the test raised KeyError in the executive. A test nothing bound cannot
    hold: the way is passed over and the goal ends failed with its reason."""
    from agents.lang.core.matcher import solve
    from agents.lang.core.terms import Test, Var

    program = load_program_text("""
((near ?x ?d) :percepts ((thing ?x dist ?d)) :tests ((< ?d 5)))
((reached ?x) :percepts ((thing ?x)) :relations ((near ?x ?d)) :tests ((< (* 2 ?d) 8)))
""", "t.tlp")
    engine = Engine(program)
    state = engine.add_goal(engine.initial_state(), "(reached A)", 1)
    result = engine.cycle(state, [["thing", "A", "dist", 10.0]])
    report = result.decision.goals[0]
    assert report.status in (GoalStatus.FAILED, GoalStatus.IMPASSE), report
    test = next(t for t in program.concepts["reached"][0].tests if isinstance(t, Test))
    assert list(solve([test], {Var("x"): "A"}, None, None)) == []
