"""A user's goal written as a concept (issue 31): its relations are pursued in the order the
same relations written as ``(and ...)`` would be (goal regression, agents/lang/solving/
ordering.py), and an existential concept takes the binding that needs the fewest actions.
Run by the pure engine against the real pymunk Blocks World, replayed under STRIPS rules."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, load_program_text

from ..conftest import BLOCKS
from .blocksworld import random_state, run

ENGINE = Engine(load_program_text(BLOCKS.read_text() + """
(concepts
  ((tower3 ?a ?b ?c)
   :relations ((on ?a ?b) (on ?b ?c)))
  ((d-on-something)
   :relations ((on D ?x) (clear D))))
""", "towers.tlp"))
NAMES = ["A", "B", "C", "D", "E"]


def test_a_concept_goal_is_ordered_as_its_conjunction():
    """A B C one tower (A at the bottom): (tower3 A B C) takes the six actions of (and (on A B)
    (on B C)); before issue 31 it took twelve (A onto B first, then undone)."""
    start = (("A", "B", "C"),)
    concept = run(ENGINE, start, [("(tower3 A B C)", 5)], 60)
    conj = run(ENGINE, start, [("(and (on A B) (on B C))", 5)], 60)
    assert concept.statuses[-1] == conj.statuses[-1] == {"g1": "satisfied"}
    assert concept.plan == conj.plan and len(concept.plan) == 6


def test_an_existential_concept_takes_the_cheapest_binding():
    """(d-on-something) after a tower A B C: D onto C (two actions), not onto A (six)."""
    r = run(ENGINE, (("A", "B", "C"), ("D",)), [("(d-on-something)", 5)], 30)
    assert r.statuses[-1] == {"g1": "satisfied"}
    assert r.plan == [["*pickup", "D", "T"], ["*stack", "D", "C"]]


@st.composite
def problems(draw):
    rnd = draw(st.randoms(use_true_random=False))
    names = NAMES[:draw(st.integers(3, 5))]
    a, b, c = draw(st.permutations(names))[:3]
    return random_state(rnd, names), (a, b, c)


@settings(max_examples=20, deadline=None)
@given(problems())
def test_random_concept_goals_take_no_more_actions_than_their_conjunction(problem):
    """Any state of 3..5 blocks, any three of them: (tower3 X Y Z) is achieved, the replayed
    world agrees, in no more actions than (and (on X Y) (on Y Z))."""
    start, (a, b, c) = problem
    concept = run(ENGINE, start, [(f"(tower3 {a} {b} {c})", 5)], 80)
    conj = run(ENGINE, start, [(f"(and (on {a} {b}) (on {b} {c}))", 5)], 80)
    assert concept.statuses[-1] == {"g1": "satisfied"}, concept.notes[-1]
    assert concept.replay.under[a] == b and concept.replay.under[b] == c
    assert len(concept.plan) <= len(conj.plan), (concept.plan, conj.plan)
