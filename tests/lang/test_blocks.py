"""Blocks World (seed 000, Figure 3) from primitive skills only: the means-ends problem solver
finds what programs/blocks.tlp no longer says, cycle by cycle against constructed states, and
learns the seed's two skills.

Seed 000, "Problem Solving and Skill Learning": "The agent is given the goal of clearing block
A, but it cannot find any applicable skill path in the current state. In response to this
impasse, it invokes problem solving, which chains off the goal using the instantiated skill
(unstack B A). This has the start condition (unstackable B A), which the system pushes onto the
goal stack. On the next cycle, the agent uses concept chaining to decompose this subgoal into
(clear B) and (hand-empty), and the system chooses the currently unsatisfied (clear B) as its
next subgoal. Since there exists an executable skill, (unstack C B), that would achieve this
subgoal, the system executes it. This produces a state in which (clear B) is true, but in which
(hand-empty) has become untrue. Therefore, the agent pushes this subgoal onto its stack and
retrieves (putdown C T), which it executes in turn. This makes (unstackable B A) true, which
means the agent can finally execute (unstack B A) to achieve the top-level goal (clear A)."
"""

from __future__ import annotations

import pytest

from agents.lang import Engine, GoalStatus, load_program
from agents.lang.solving.learner import canonical

from .conftest import FIX, figure3_program

TOWER = {"A": "T", "B": "A", "C": "B"}   # C on B on A on the table T


def percepts(support: dict[str, str], holding: str | None = None) -> list[list]:
    """Percepts for blocks resting on "T" (the table) or on another block; one column per
    tower, a held block off the table at ypos 99."""
    out = [["table", "T", "xpos", 0, "ypos", 0, "height", 2],
           ["hand", "H1", "status", holding or "empty"]]
    columns: dict[str, int] = {}

    def place(b: str) -> tuple[int, int]:
        under = support[b]
        if under == "T":
            return columns.setdefault(b, 3 * len(columns)), 2
        x, y = place(under)
        return x, y + 2

    for b in sorted(support):
        x, y = (99, 99) if b == holding else place(b)
        out.append(["block", b, "xpos", x, "ypos", y, "height", 2])
    return out


def act(support: dict, holding: str | None, action: list):
    """Apply one action the way the world would; fail loudly on an illegal one."""
    name, *args = action
    if name in ("*unstack", "*pickup"):
        block, source = args
        assert holding is None and support[block] == source
        return {**support, block: "hand"}, block
    block, target = args
    assert holding == block
    return {**support, block: target}, None


def run(engine, state, support, holding=None, cycles=10):
    """(trace of (decision, actions), support, holding, last state)."""
    trace = []
    for _ in range(cycles):
        result = engine.cycle(state, percepts(support, holding))
        state = result.state
        trace.append((result.decision, [a.to_list() for a in result.decision.actions]))
        for a in result.decision.actions:
            support, holding = act(support, holding, a.to_list())
    return trace, support, holding, state


@pytest.fixture(scope="module")
def primitive():
    """programs/blocks.tlp (primitive skills only) with the problem solver (the default)."""
    return Engine(figure3_program())


@pytest.fixture(scope="module")
def figure3(primitive):
    return run(primitive, primitive.initial_state(), TOWER, cycles=6)


def test_beliefs_of_a_tower(primitive):
    beliefs = {str(b) for b in primitive.infer(percepts(TOWER))}
    assert {"(on B A)", "(on C B)", "(ontable A T)", "(clear C)", "(hand-empty)",
            "(unstackable C B)", "(above C A)", "(above C B)", "(above B A)"} <= beliefs
    assert not {"(clear A)", "(clear B)", "(on A B)", "(above A C)"} & beliefs


def test_the_program_has_primitive_skills_only(primitive):
    assert {s.kind for s in primitive.program.skills} == {"primitive"}


def test_figure3_actions_from_primitive_skills(figure3):
    trace, support, holding, _ = figure3
    assert [actions for _, actions in trace] == [
        [], [["*unstack", "C", "B"]], [["*putdown", "C", "T"]], [["*unstack", "B", "A"]], [], []]
    assert support == {"A": "T", "B": "hand", "C": "T"} and holding == "B"
    assert trace[4][0].goals[0].status is GoalStatus.SATISFIED


def test_figure3_goal_stack_per_cycle_follows_the_seed(figure3):
    trace = figure3[0]
    stacks = [(d.section("solver").stack("p1") if d.section("solver") else None)
              for d, _ in trace]
    assert stacks == [
        ["(clear A)", "(unstackable B A)"],                  # skill chaining off (unstack B A)
        ["(clear A)", "(unstackable B A)", "(clear B)"],     # concept chaining; (unstack C B)
        ["(clear A)", "(unstackable B A)", "(hand-empty)"],  # (hand-empty) became untrue
        ["(clear A)"],                                       # (unstack B A) is executable
        [],                                                  # (clear A) holds: solved
        None]                                                # nothing left to solve
    whys = [e["why"] for e in trace[2][0].section("solver").to_dict()["stacks"][0]["entries"]]
    assert whys == [
        "goal p1 in impasse",
        "chained off skill (unstack B A) because its start (unstackable B A) is false",
        "decomposed (unstackable B A) through concept unstackable#1 into (on B A) (clear B) "
        "(hand-empty); (hand-empty) does not hold"]
    assert [d.goals[0].status for d, _ in trace[:4]] == [
        GoalStatus.IMPASSE, GoalStatus.ACTIVE, GoalStatus.ACTIVE, GoalStatus.ACTIVE]
    assert trace[0][0].goals[0].note == "problem solving: pushed (unstackable B A)"
    # problem solving ran on cycles 0-2; on cycle 3 the executive found (unstack B A) itself
    assert [d.section("solver").solving for d, _ in trace[:5]] == [("p1",)] * 3 + [()] * 2
    assert [s.skill for s in trace[1][0].path] == ["clear#1"]   # (clear B) <- (unstack C B)


def test_figure3_explanation_text(figure3):
    text = figure3[0][0][0].explain()
    assert "goal stack of p1 (problem solving since cycle 0):" in text
    assert "  2 (unstackable B A)  <- chained off skill (unstack B A) because its start " \
           "(unstackable B A) is false" in text


def test_figure3_learns_the_seeds_two_skills(figure3):
    """The seed's learned skills, as the hand-written program had them: (clear ?b) by
    (unstackable ?c ?b) then (clear ?b), started when (on ?c ?b); (unstackable ?b ?from) by
    (clear ?b) then (hand-empty), started when (on ?b ?from)."""
    state = figure3[3]
    assert len(state.learned) == 2
    learned = Engine(figure3_program()).executive_for(state)
    new = learned.program.skills[-2:]
    seed = load_program(FIX / "blocks_handwritten.tlp")
    want = [next(s for s in seed.skills if s.name == name)
            for name in ("unstackable#1", "clear#2")]
    assert [canonical(s) for s in new] == [canonical(s) for s in want]
    assert state.learned[0].endswith("((unstackable ?b1 ?b2)\n"
                                     " :percepts ((block ?b1) (block ?b2))\n"
                                     " :start ((on ?b1 ?b2))\n"
                                     " :subgoals ((clear ?b1) (hand-empty)))")
    assert state.learned[0].startswith(
        "; learned at cycle 3 from problem (clear A) (goal p1): (unstackable B A) by concept "
        "chaining on unstackable#1\n")
    assert "((clear ?b1)\n :percepts ((block ?b1) (block ?b2))\n :start ((on ?b2 ?b1))\n " \
           ":subgoals ((unstackable ?b2 ?b1) (clear ?b1)))" in state.learned[1]
    trace = figure3[0]
    assert trace[3][0].section("solver").learned == (state.learned[0],)
    assert trace[4][0].section("solver").learned == (state.learned[1],)


def test_transfer_a_renamed_problem_runs_with_no_impasse(primitive, figure3):
    """Z on Y on X, goal (clear X), with the skills learned on Figure 3: pure execution."""
    state = primitive.add_goal(primitive.initial_state(learned=figure3[3].learned), "(clear X)",
                               priority=0, goal_id="g1")
    state = primitive.remove_goal(state, "p1")
    trace, support, _, end = run(primitive, state, {"X": "T", "Y": "X", "Z": "Y"}, cycles=5)
    assert [actions for _, actions in trace] == [
        [["*unstack", "Z", "Y"]], [["*putdown", "Z", "T"]], [["*unstack", "Y", "X"]], [], []]
    for decision, _ in trace:
        assert all(g.status is not GoalStatus.IMPASSE for g in decision.goals)
        assert decision.section("solver") is None
    assert [s.skill for s in trace[0][0].path] == ["clear#3", "unstackable#1", "clear#1"]
    assert end.learned == figure3[3].learned and end.solver.stacks == ()


def test_stack_a_on_c_from_a_tower(primitive):
    state = primitive.add_goal(primitive.initial_state(), "(on A C)", priority=0)
    trace, support, holding, state = run(primitive, state, {"A": "T", "B": "A", "C": "T"},
                                         cycles=9)
    assert [a for _, actions in trace for a in actions] == [
        ["*unstack", "B", "A"], ["*putdown", "B", "T"], ["*pickup", "A", "T"],
        ["*stack", "A", "C"]]
    assert support["A"] == "C" and holding is None
    assert [t.splitlines()[1] for t in state.learned] == [
        "((pickupable ?b1 ?t1)", "((holding ?b1)", "((stackable ?b1 ?b2)", "((on ?b1 ?b2)"]
    # goal p1 (clear A) was satisfied throughout the (on A C) work but is rechecked each cycle
    assert trace[-1][0].goals[0].status is GoalStatus.SATISFIED


def test_goal_with_variable_puts_every_block_on_the_table(primitive):
    state = primitive.remove_goal(primitive.initial_state(), "p1")
    state = primitive.add_goal(state, "(ontable ?b T)")
    trace, support, _, _ = run(primitive, state, TOWER, cycles=10)
    assert support == {"A": "T", "B": "T", "C": "T"}
    assert trace[-1][0].goals[0].status is GoalStatus.SATISFIED
    assert trace[0][0].goals[0].instance == "(ontable B T)"
