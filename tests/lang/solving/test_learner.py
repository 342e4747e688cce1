"""Skill learning from the goal stack (agents/lang/solving/learner.py, seed 000): what a
skill-chaining and a concept-chaining entry teach, the ambiguous (hand-empty) case, skills
learned through an existing skill, generalisation, and no duplicates."""

from __future__ import annotations

import pytest

from agents.lang import Engine, Literal, as_percepts, load_program
from agents.lang.core.store import PerceptIndex, store_of
from agents.lang.solving.learner import canonical, generalise, learn
from agents.lang.solving.state import CONCEPT, Alternative, StackEntry
from agents.lang.solving.task import Task

from ..conftest import BLOCKS, ROOT, figure3_program
from ..test_blocks import TOWER, percepts, run

BLOCKS_TEXT = BLOCKS.read_text()
UNSTACKABLE = Alternative(CONCEPT, 1, "unstackable#1", (("b", "B"), ("from", "A")),
                          ("(on B A)", "(clear B)", "(hand-empty)"), "concept unstackable#1")


@pytest.fixture(scope="module")
def blocks():
    return Engine(figure3_program())


def _task(engine, support, holding=None) -> Task:
    index = PerceptIndex(as_percepts(percepts(support, holding)))
    return Task(engine.program, index, store_of(engine.infer(index)))


def test_ambiguous_case_a_subconcept_made_false_and_achieved_again_is_a_subgoal(blocks):
    """(hand-empty) held when (unstackable B A) was decomposed, became false after (unstack
    C B) and was achieved again: it is the last subgoal, and not part of the start."""
    task = _task(blocks, {"A": "T", "B": "A", "C": "T"})        # after (putdown C T)
    entry = StackEntry("(unstackable B A)", alternatives=(UNSTACKABLE,), chosen=0,
                       initial=("(on B A)", "(hand-empty)"),
                       order=("(clear B)", "(hand-empty)"))
    new = learn(task, entry, "test", {})
    assert str(new.skill.head) == "(unstackable ?b1 ?b2)"
    assert [str(c) for c in new.skill.start] == ["(on ?b1 ?b2)"]
    assert [str(g) for g in new.skill.subgoals] == ["(clear ?b1)", "(hand-empty)"]
    assert new.start == ("(on B A)",)   # ground, for the skill chained above it


def test_the_other_reading_would_make_a_skill_that_cannot_work(blocks):
    """Were (hand-empty) part of the start (it held initially) and not a subgoal, the skill
    would end with the hand full and (unstackable B A) false: the executive could not go on."""
    text = """((unstackable ?b1 ?b2) :percepts ((block ?b1) (block ?b2))
                :start ((on ?b1 ?b2) (hand-empty)) :subgoals ((clear ?b1)))"""
    engine = Engine(blocks.program, solver=None)
    state = engine.initial_state(learned=(text,))
    state = engine.add_goal(engine.remove_goal(state, "p1"), "(unstackable B A)", 0, "g1")
    trace, *_ = run(engine, state, TOWER, cycles=2)
    assert [acts for _, acts in trace] == [[["*unstack", "C", "B"]], []]
    assert any(w.reason == "every subgoal already holds (goal still false)"
               for w in trace[1][0].why)


def test_an_entry_achieved_through_an_existing_skill_teaches_nothing(blocks):
    """With the learned (unstackable ?b1 ?b2) skill, Figure 3's (unstackable B A) has an
    executable path as soon as it is pushed: no decision, nothing to learn for it; the (clear
    ?b1) skill learned above it takes its start from that skill's start, (on ?b2 ?b1)."""
    _, _, _, first = run(blocks, blocks.initial_state(), TOWER, cycles=6)
    trace, _, _, state = run(blocks, blocks.initial_state(learned=first.learned[:1]), TOWER,
                             cycles=5)
    assert [a for _, acts in trace for a in acts] == [
        ["*unstack", "C", "B"], ["*putdown", "C", "T"], ["*unstack", "B", "A"]]
    assert "p1: executing (unstackable B A) by unstackable#1" in \
        trace[0][0].section("solver").events
    assert trace[2][0].section("solver").events == ("p1: achieved (unstackable B A)",)
    assert len(state.learned) == 2   # the one started from, and (clear ?b1) learned anew
    assert state.learned[1].split("\n", 1)[1] == first.learned[1].split("\n", 1)[1]


def test_no_duplicate_of_a_known_skill_is_added(blocks):
    task = _task(blocks, {"A": "T", "B": "A", "C": "T"})
    entry = StackEntry("(unstackable B A)", alternatives=(UNSTACKABLE,), chosen=0,
                       initial=("(on B A)", "(hand-empty)"),
                       order=("(clear B)", "(hand-empty)"))
    known: dict[str, str] = {}
    assert learn(task, entry, "first", known).duplicate == ""
    again = learn(task, entry, "second", known)
    assert again.duplicate == "learned unstackable"
    written = load_program(ROOT / "tests" / "lang" / "fixtures" / "blocks_handwritten.tlp")
    hand = {canonical(s): s.name for s in written.skills}
    assert learn(task, entry, "third", hand).duplicate == "unstackable#1"


def test_generalise_names_variables_by_percept_type_and_keeps_other_constants(blocks):
    task = _task(blocks, TOWER)
    skill = generalise(task, Literal("on", ("C", "B")), [Literal("ontable", ("B", "T"))],
                       [Literal("on", ("C", 4))])
    assert str(skill.head) == "(on ?b1 ?b2)"
    assert [str(p) for p in skill.percepts] == ["(block ?b1)", "(block ?b2)", "(table ?t1)"]
    assert [str(g) for g in skill.subgoals] == ["(on ?b1 4)"]   # 4 is no percept's id
    assert [str(c) for c in skill.start] == ["(ontable ?b2 ?t1)"]


GOAL_STATE = """
(concepts
  ((goal-state) :relations ((on B2 B1) (on B1 B3))))
"""


def test_an_object_the_head_does_not_name_stays_a_constant():
    """Issue 22: from a goal without arguments, concept chaining used to learn
    ((goal-state) :percepts ((block ?b1) (block ?b2)) :subgoals ((on ?b1 ?b2))), whose
    variables no start ties to anything, so it "applied" to any two blocks. Now a learned
    skill's variables are the goal's constants and what a positive :start literal ties to
    them; here the goal has none, so B2 and B1 stay as written."""
    from agents.lang import load_program_text

    program = load_program_text(BLOCKS_TEXT + GOAL_STATE, "goal-state.tlp")
    engine = Engine(program)
    state = engine.add_goal(engine.initial_state(), "(goal-state)", 1, "g1")
    trace, support, _, state = run(engine, state, {"B1": "T", "B2": "T", "B3": "T"}, cycles=20)
    assert support == {"B1": "B3", "B2": "B1", "B3": "T"}
    learned = Engine(program).executive_for(engine.initial_state(learned=state.learned))
    skills = learned.program.skills[len(program.skills):]
    assert skills
    for s in skills:
        tied = set(s.head.variables())
        for c in s.start:
            if isinstance(c, Literal) and not c.negated and c.variables() & tied:
                tied |= c.variables()
        used = {v for g in (*s.subgoals, *s.start) for v in g.variables()}
        assert used <= tied, str(s.head)
    heads = [str(s.head) for s in skills]
    assert "(goal-state)" in heads
    goal_skill = skills[heads.index("(goal-state)")]
    assert [str(g) for g in goal_skill.subgoals] == ["(on B1 B3)", "(on B2 B1)"]
    again = Engine(program)
    fresh = again.add_goal(again.initial_state(learned=state.learned), "(goal-state)", 1, "g1")
    trace, support, *_ = run(again, fresh, {"B1": "T", "B2": "T", "B3": "T"}, cycles=20)
    assert support == {"B1": "B3", "B2": "B1", "B3": "T"}
    other = again.add_goal(again.initial_state(learned=state.learned), "(on B3 B2)", 1, "g1")
    trace, support, *_ = run(again, other, {"B1": "T", "B2": "T", "B3": "T"}, cycles=20)
    assert support["B3"] == "B2"
