"""Priorities during problem solving (seed 000, "Adding Goal Priorities"): a violated or new
higher goal pre-empts problem solving on a lower one. The lower goal's stack is kept and
resumed, not rebuilt: it keeps its entries, decisions and start cycle, is brought up to date
every cycle (what the higher goal's actions achieve is popped, what they undo is noted), and
solving goes on from its top when the goal is reached again."""

from __future__ import annotations

import pytest

from agents.lang import Engine, GoalStatus, load_program_text

from ..conftest import figure3_program
from ..test_blocks import TOWER, act, percepts


@pytest.fixture(scope="module")
def blocks():
    return Engine(figure3_program())


def _cycles(engine, state, support, n, post=None):
    """Run n cycles; ``post``: {cycle: (goal, priority, id)} added before that cycle."""
    holding, out = None, []
    for c in range(n):
        if post and c in post:
            state = engine.add_goal(state, *post[c])
        result = engine.cycle(state, percepts(support, holding))
        state = result.state
        out.append(result.decision)
        for a in result.decision.actions:
            support, holding = act(support, holding, a.to_list())
    return out, state


def _stacks(decision):
    section = decision.section("solver")
    return {} if section is None else {s.goal_id: (s.started, s.goals())
                                       for s in section.stacks}


def test_a_violated_higher_goal_preempts_and_the_stack_is_kept_and_resumed(blocks):
    """(hand-empty) above (clear A): after (unstack C B) the hand is full, so g0 puts C down
    (its own skill path) while p1's stack waits; then p1 goes on from its stack, and what it
    learns counts (hand-empty) as achieved again (by g0's action)."""
    state = blocks.add_goal(blocks.initial_state(), "(hand-empty)", 0, "g0")
    decisions, state = _cycles(blocks, state, dict(TOWER), 6)
    assert [[str(a) for a in d.actions] for d in decisions] == [
        [], ["(*unstack C B)"], ["(*putdown C T)"], ["(*unstack B A)"], ["(*putdown B T)"], []]
    assert decisions[2].status_of("g0") is GoalStatus.ACTIVE
    assert decisions[2].status_of("p1") is GoalStatus.SUSPENDED
    assert decisions[2].section("solver").solving == ()          # no problem solving on p1
    assert _stacks(decisions[1])["p1"] == (0, ["(clear A)", "(unstackable B A)", "(clear B)"])
    assert _stacks(decisions[2])["p1"] == (0, ["(clear A)", "(unstackable B A)"])  # kept
    assert _stacks(decisions[3])["p1"] == (0, ["(clear A)"])
    assert decisions[4].status_of("p1") is GoalStatus.SATISFIED
    fig3 = Engine(blocks.program)
    _, alone = _cycles(fig3, fig3.initial_state(), dict(TOWER), 6)
    assert [t.split("\n", 1)[1] for t in state.learned] == \
        [t.split("\n", 1)[1] for t in alone.learned]


def test_a_new_higher_goal_in_impasse_gets_its_own_stack_beside_the_kept_one(blocks):
    """p1 (clear A) has pushed (unstackable B A) when g0 (clear D) is posted above it: g0 is
    solved on its own stack while p1's stays as it was; then p1 resumes from that stack (the
    skills learned on g0 meanwhile carry it without further search)."""
    world = {**TOWER, "D": "T", "E": "D", "F": "E"}
    decisions, state = _cycles(blocks, blocks.initial_state(), world, 11,
                               post={1: ("(clear D)", 0, "g0")})
    kept = (0, ["(clear A)", "(unstackable B A)"])
    assert _stacks(decisions[1]) == {"g0": (1, ["(clear D)", "(unstackable E D)"]), "p1": kept}
    for d in decisions[1:5]:
        assert _stacks(d)["p1"] == kept and d.status_of("p1") is GoalStatus.PENDING
        assert d.section("solver").solving in (("g0",), ())
    assert decisions[5].status_of("g0") is GoalStatus.SATISFIED
    assert _stacks(decisions[5])["p1"] == (0, ["(clear A)", "(unstackable B A)", "(clear B)"])
    assert decisions[5].section("solver").solving == ("p1",)
    assert [str(a) for d in decisions[5:] for a in d.actions] == [
        "(*putdown E T)", "(*unstack C B)", "(*putdown C T)", "(*unstack B A)"]
    assert decisions[10].status_of("p1") is GoalStatus.SATISFIED


LAW = """
(concepts
  ((stopped ?self) :percepts ((self ?self speed ?s)) :tests ((= ?s 0)))
  ((at-desired-speed ?self) :percepts ((self ?self speed ?speed limit ?limit))
   :tests ((<= ?speed (- ?limit 5)) (> ?speed (- ?limit 15))))
  ((delivered ?self) :percepts ((self ?self parcel gone))))
(skills
  ((at-desired-speed ?self) :percepts ((self ?self)) :start ((stopped ?self))
   :actions ((*gas 6.25)))
  ((delivered ?self) :percepts ((self ?self)) :actions ((*deliver))))
(goals (at-desired-speed ?self))
"""


def test_a_failed_law_blocks_the_errand_and_acts_again_as_soon_as_a_skill_for_it_is_executable():
    """Seed 000, Tables 1 and 2: "when the agent's vehicle is stopped, the agent should invoke
    the action (*gas 6.25)". Too fast, nothing can slow the car: the solver gives the law up,
    and the errand still waits ("the agent considers a goal only when all more important goals
    are satisfied"); once the car stands, Table 1's skill is executable and the law acts again
    (the goal list is rechecked every cycle); then the errand goes on."""
    engine = Engine(load_program_text(LAW, "law.tlp"))
    state = engine.add_goal(engine.initial_state(), "(delivered ME)", priority=5, goal_id="g1")
    trace = []
    for speed in (30.0, 30.0, 30.0, 0.0, 20.0):
        result = engine.cycle(state, [["self", "ME", "speed", speed, "limit", 25,
                                       "parcel", "held"]])
        state = result.state
        trace.append(([(g.id, g.status) for g in result.decision.goals],
                      [a.to_list() for a in result.decision.actions]))
    assert trace == [
        ([("p1", GoalStatus.IMPASSE), ("g1", GoalStatus.PENDING)], []),
        ([("p1", GoalStatus.FAILED), ("g1", GoalStatus.PENDING)], []),
        ([("p1", GoalStatus.FAILED), ("g1", GoalStatus.PENDING)], []),
        ([("p1", GoalStatus.ACTIVE), ("g1", GoalStatus.PENDING)], [["*gas", 6.25]]),
        ([("p1", GoalStatus.SATISFIED), ("g1", GoalStatus.ACTIVE)], [["*deliver"]])]
    assert state.failure_of("p1") is None
