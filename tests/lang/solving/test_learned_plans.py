"""Learned skills never lengthen a plan (issue 31, "Learned skills lengthen some plans"): with
skills learned on other problems, a Blocks World conjunction is solved in no more actions than
without them, run by the pure engine against the real pymunk Blocks World and replayed under
STRIPS rules (tests/lang/solving/blocksworld.py; towers bottom first).

The skills are those the solver learned on two earlier problems ((and (on B1 B2) (on B3 B1))
and (and (on B4 B3) (on B3 B2)), random problems of 3 and 4 blocks): a skill to clear a block
and one to pick one up let the agent pursue (on B2 B8) at once, putting B3 on the table to free
B2, where without them it first moves B6 onto B5, which lets B3 go straight onto B7."""

from __future__ import annotations

from agents.lang import Engine, load_program

from ..conftest import BLOCKS
from .blocksworld import conjunction, run

ENGINE = Engine(load_program(BLOCKS))

LEARNED = (
    "((stackable ?b1 ?b2)\n :percepts ((block ?b1) (block ?b2))\n"
    " :subgoals ((clear ?b2) (holding ?b1)))",
    "((on ?b1 ?b2)\n :percepts ((block ?b1) (block ?b2))\n"
    " :subgoals ((stackable ?b1 ?b2) (on ?b1 ?b2)))",
    "((unstackable ?b1 ?b2)\n :percepts ((block ?b1) (block ?b2))\n :start ((on ?b1 ?b2))\n"
    " :subgoals ((clear ?b1) (hand-empty)))",
    "((clear ?b1)\n :percepts ((block ?b1) (block ?b2))\n :start ((on ?b2 ?b1))\n"
    " :subgoals ((unstackable ?b2 ?b1) (clear ?b1)))",
    "((pickupable ?b1 ?t1)\n :percepts ((block ?b1) (table ?t1))\n :start ((ontable ?b1 ?t1))\n"
    " :subgoals ((clear ?b1) (hand-empty)))",
    "((holding ?b1)\n :percepts ((block ?b1) (table ?t1))\n :start ((ontable ?b1 ?t1))\n"
    " :subgoals ((pickupable ?b1 ?t1) (holding ?b1)))",
)

START = (("B2", "B3", "B4"), ("B1", "B7", "B6", "B5"), ("B8",))
FACTS = [("B8", "B4"), ("B2", "B8"), ("B7", "B1"), ("B3", "B7"), ("B6", "B5")]


def _plan(learned: tuple[str, ...]) -> list:
    out = run(ENGINE, START, [(conjunction(FACTS), 1)], 120, learned)
    assert out.replay.holds(FACTS), (learned, out.plan, out.notes[-1])
    return out.plan


def test_skills_learned_elsewhere_make_no_plan_longer_than_solving_afresh():
    fresh = _plan(())
    learned = _plan(LEARNED)
    assert len(fresh) == 12, fresh   # the optimum: B4 and B5 off, six blocks moved once
    assert len(learned) <= len(fresh), (fresh, learned)


def test_the_learned_skills_still_save_problem_solving():
    fresh = run(ENGINE, START, [(conjunction(FACTS), 1)], 120)
    again = run(ENGINE, START, [(conjunction(FACTS), 1)], 120, LEARNED)
    assert again.solving < fresh.solving, (fresh.solving, again.solving)
