"""`teleo check` reports every error in a body at file:line:col (issue 9): unknown
construct, misplaced modifier, a do-best alternative without :utility, unbound variables,
an action or subgoal that cannot exist."""

from __future__ import annotations

import pytest

from agents.lang import ProgramError, load_program_text
from tests.lang.scs.drive import PRELUDE


def errors(body: str, extra: str = "") -> list[str]:
    text = PRELUDE + extra + f"\n(skills ((never ?x) :percepts ((self ?x))\n :body {body}))"
    with pytest.raises(ProgramError) as info:
        load_program_text(text, "b.tlp")
    return [str(d) for d in info.value.errors]


LINE = PRELUDE.count("\n") + 3   # the line of :body


def test_an_unknown_construct_is_named_with_a_suggestion():
    assert errors("(do (repaet (*a)))") == [
        f"b.tlp:{LINE}:13: unknown construct 'repaet' (did you mean 'repeat'?); constructs "
        "are do, do*, do-all, do*-all, do-any, do*-any, do-first, do*-first, do-best, "
        "do*-best, repeat, repeat*, atomic, assert, retract, wait"]
    assert errors("(do (dox))") == [
        f"b.tlp:{LINE}:12: (dox) in the body of skill never#1 is neither a construct nor a "
        "defined concept (did you mean 'do'?)"]


def test_misplaced_and_unknown_modifiers():
    found = errors("(do (*a) :while ((flag x)) (*b))")
    assert found == [f"b.tlp:{LINE}:17: modifier :while is misplaced: in (do ...) modifiers "
                     "come before the steps"]
    assert "modifier :when is misplaced" in errors("(do (:when ((flag x))))")[0]
    assert "unknown modifier :whilst in (do ...) (did you mean ':while'?)" in \
        errors("(do :whilst ((flag x)) (*a))")[0]
    assert "is misplaced: put it after the construct's name" in \
        errors("(do-first (((flag x)) :while ((flag y)) (*a)))")[0]


def test_a_do_best_alternative_needs_a_utility():
    found = errors("(do-best (((flag x)) :utility 3 (*a)) (((flag y)) (*b)))")
    assert found == [f"b.tlp:{LINE}:46: alternative of (do-best ...) has no :utility; "
                     "write (CONDS :utility EXPR STEP)"]


def test_unbound_variables_in_steps_utilities_and_conditions():
    found = errors("(do-best (((flag ?y)) :utility ?u (*a ?z)) (() :utility 1 (*b ?y)))")
    assert any("variable ?u in :utility ?u of an alternative of (do-best ...) is bound "
               "nowhere" in e for e in found)
    assert any("variable ?z in action (*a ?z) is bound nowhere" in e for e in found)
    assert any("variable ?y in action (*b ?y) is bound nowhere" in e for e in found)
    assert len(found) == 3


def test_when_and_while_bind_for_the_steps_inside_until_and_unless_do_not():
    assert errors("(do :when ((flag ?f)) :until ((flag ?g)) (*a ?f ?g))") == [
        f"b.tlp:{LINE}:49: variable ?g in action (*a ?f ?g) is bound nowhere; bind it in the "
        "head, :percepts, :start, :requires or an enclosing condition"]


def test_actions_and_subgoals_that_cannot_exist():
    found = errors("(do (*gass 1) (flag x) (nver ?x) (never ?x ?x))")
    assert any(f"b.tlp:{LINE}:12: action *gass in the body of skill never#1 cannot exist: "
               "the actions listed in (resources ...) are *a, *b, *c, *d, *e" in e
               for e in found)
    assert any("subgoal (flag x) in the body of skill never#1 cannot be achieved: no skill "
               "has flag as its head" in e for e in found)
    assert any("(nver ?x) in the body of skill never#1 is neither a construct nor a defined "
               "concept (did you mean 'never'?)" in e for e in found)
    assert any("concept never takes 1 argument(s), got 2" in e for e in found)


def test_asserted_facts_define_model_predicates_with_one_arity():
    found = errors("(do (assert (seen ?x)) (retract (seen ?x 1)) (assert (seen ?q)))")
    assert any("(seen ?x 1) (fact of (retract (seen ?x 1))): concept seen takes 1 "
               "argument(s), got 2" in e for e in found)
    assert any("variable ?q in fact of (assert (seen ?q)) is bound nowhere" in e
               for e in found)


def test_shapes_of_constructs_and_alternatives():
    assert "(do ...) has no steps" in errors("(do :while ((flag x)))")[0]
    assert "each alternative of (do-first ...) is (CONDS STEP)" in \
        errors("(do-first (*a))")[0]
    assert "needs exactly one step after its conditions" in \
        errors("(do-first (((flag x)) (*a) (*b)))")[0]
    assert "(atomic ...) holds only actions" in errors("(atomic (*a) (do (*b)))")[0]
    assert "(wait CONDS) needs its conditions: one condition such as (lamp-on L1)" in \
        errors("(wait)")[0]
    assert "(assert (FACT)) takes exactly one fact" in errors("(assert (a 1) (b 2))")[0]


def test_a_valid_body_loads_and_every_construct_is_accepted():
    body = """(do* :while ((flag go)) :until ((flag stop))
         (atomic (*a) (assert (seen ?x)))
         (do-all (*b) (do-any (*c) (*d)))
         (do*-all (*b)) (do*-any (*c))
         (do-first (((flag x)) (*a)) (() (*b))) (do*-first (() (*c)))
         (do-best (((flag ?f)) :utility 2 :reward 1 (*a ?f)) (() :utility 1 (*b)))
         (do*-best (() :utility 1 (*e)))
         (repeat :when ((flag r)) (*a)) (repeat* :unless ((flag s)) (*b))
         (wait (flag go) (flag x))
         (retract (seen ?x)))"""
    text = PRELUDE + f"(skills ((never ?x) :percepts ((self ?x)) :body {body}))"
    program = load_program_text(text, "ok.tlp")
    assert program.skills[0].kind == "body"
