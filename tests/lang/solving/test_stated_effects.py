"""A primitive skill's `:effects` (agents/lang/execution/effects.py): what its action achieves
besides the head and what it makes false, read into the effect model the executive's
protection and the solver's ordering use; refused on a skill without `:actions`."""

from __future__ import annotations

import pytest

from agents.lang import ProgramError, load_program_text
from agents.lang.core.terms import Action, Literal, Var
from agents.lang.execution.effects import Effects
from agents.lang.reading.printer import program_text

PROGRAM = """
(concepts
  ((on ?x ?y) :percepts ((on _ arg1 ?x arg2 ?y)))
  ((clear ?x) :percepts ((clear _ arg1 ?x)))
  ((holding ?x) :percepts ((holding _ arg1 ?x)))
  ((ontable ?x) :percepts ((ontable _ arg1 ?x))))
(skills
  ((on ?x ?y)
   :percepts ((block ?x) (block ?y))
   :start ((holding ?x) (clear ?y))
   :actions ((*stack ?x ?y))
   {stack})
  ((holding ?x)
   :percepts ((block ?x))
   :start ((clear ?x) (ontable ?x))
   :actions ((*pick-up ?x))
   {pickup})
  ((holding ?x)
   :percepts ((block ?x) (block ?y))
   :start ((clear ?x) (on ?x ?y))
   :actions ((*unstack ?x ?y))
   {unstack}))
"""
EFFECTS = {"stack": ":effects ((clear ?x) (not (holding ?x)) (not (clear ?y)))",
           "pickup": ":effects ((not (ontable ?x)) (not (clear ?x)))",
           "unstack": ":effects ((clear ?y) (not (on ?x ?y)) (not (clear ?x)))"}


def program(with_effects: bool = True) -> str:
    return PROGRAM.format(**{k: v if with_effects else "" for k, v in EFFECTS.items()})


def test_an_action_achieves_its_head_and_effects_and_undoes_its_deletes():
    effects = Effects(load_program_text(program()))
    achieved, undone = effects.of_actions((Action("*stack", ("a", "b")),))
    assert set(achieved) == {Literal("on", ("a", "b")), Literal("clear", ("a",))}
    assert {Literal("holding", ("a",)), Literal("clear", ("b",))} <= set(undone)


def test_achieving_a_literal_undoes_what_every_way_to_it_deletes():
    effects = Effects(load_program_text(program()))
    assert Literal("clear", ("b",)) in effects.undoes(Literal("on", ("a", "b")))
    held = effects.undoes(Literal("holding", ("a",)))
    assert Literal("clear", ("a",)) in held                 # both ways delete it
    assert not any(p.pred in ("ontable", "on") for p in held)   # only one way each
    assert effects.achieved_with(Literal("on", ("a", "b"))) == (Literal("clear", ("a",)),)
    assert effects.achieved_with(Literal("holding", ("a",))) == ()


def test_a_program_without_effects_predicts_as_before():
    effects = Effects(load_program_text(program(with_effects=False)))
    achieved, undone = effects.of_actions((Action("*stack", ("a", "b")),))
    assert achieved == (Literal("on", ("a", "b")),) and undone == ()
    assert effects.undoes(Literal("on", ("a", "b"))) == ()
    assert not any(isinstance(a, Var) for a in achieved[0].args)


def test_effects_print_back_and_are_checked():
    read = load_program_text(program())
    text = program_text(read)
    assert ":effects ((clear ?x) (not (holding ?x)) (not (clear ?y)))" in text
    assert program_text(load_program_text(text)) == text
    assert [s.effects for s in load_program_text(text).skills] == \
        [s.effects for s in read.skills]
    with pytest.raises(ProgramError, match=r":effects are those of a primitive skill"):
        load_program_text(program().replace(":actions ((*unstack ?x ?y))",
                                            ":subgoals ((clear ?x))"))
    with pytest.raises(ProgramError, match="holdng"):
        load_program_text(program().replace("(not (holding ?x)) (not (clear ?y))",
                                            "(not (holdng ?x)) (not (clear ?y))"))
