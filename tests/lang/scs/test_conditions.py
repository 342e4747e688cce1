"""CONDS in both forms (issue 23, item 4): seed 002's ``K1 -> S1`` written directly,
``(do-first ((lamp-on L1) (*one ?j)) ...)``, as well as a list of conditions
``(((lamp-on L1)) (*one ?j))``, everywhere conditions appear (do-first and do-best
alternatives, ``:while``/``:until``/``:when``/``:unless``, ``wait``); ``()`` is always true;
anything else is refused at file:line:col with the forms expected."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import ProgramError, load_program_text
from tests.lang.scs.drive import PRELUDE, Driver, body_program

LAMPS = "(concepts ((lamp-on ?l) :percepts ((lamp ?l on T))))"

# each construct, its conditions written as {c} (one literal, or a list of one)
CONSTRUCTS = {
    "do-first": "(do-first ({c} (*a)) (() (*b)))",
    "do*-first": "(do*-first ({c} (*a)) (() (*b)))",
    "do-best": "(do-best ({c} :utility 9 (*a)) (() :utility 1 (*b)))",
    "do*-best": "(do*-best ({c} :utility 9 (*a)) (() :utility 1 (*b)))",
    ":while": "(do (*e) (do :while {c} (*a) (*a)) (*b))",
    ":until": "(do (*e) (do :until {c} (*a) (*a)) (*b))",
    ":when": "(do-any (do :when {c} (*a)) (*b))",
    ":unless": "(do-any (do :unless {c} (*a)) (*b))",
    "wait": "(do (*e) (wait {c}) (*a))",
}
FORMS = {"literal": "{lit}", "list": "({lit})"}


def run(body: str, flags: list[list[str]], seed: int = 0) -> list[str]:
    d = Driver(body_program(body), seed)
    return d.run(len(flags), lambda k: flags[k])


@pytest.mark.parametrize("where", CONSTRUCTS)
def test_every_construct_reads_one_literal_as_its_list_of_one(where):
    flags = [["x"], [], ["x"], ["x"], [], [], ["x"], ["x"]]
    traces = {form: run(CONSTRUCTS[where].format(c=shape.format(lit="(flag x)")), flags)
              for form, shape in FORMS.items()}
    assert traces["literal"] == traces["list"]
    negated = {form: run(CONSTRUCTS[where].format(c=shape.format(lit="(not (flag x))")), flags)
               for form, shape in FORMS.items()}
    assert negated["literal"] == negated["list"]
    assert traces["literal"] != negated["literal"]     # the condition is read, not ignored


def test_the_seeds_k_to_s_written_directly():
    """(do-first ((lamp-on L1) (*one ?j)) ...): the clause's condition is the one literal."""
    body = "(do-first ((lamp-on ?j) (*a ?j)) (() (*b)))"
    d = Driver(body_program(body, LAMPS))
    assert d.step(extra=[["lamp", "L1", "on", "T"]]) == [["*a", "L1"]]
    assert d.step(extra=[["lamp", "L1", "on", "NIL"]]) == [["*b"]]
    d = Driver(body_program("(do-first ((lamp-on L1) (*a 1)) (() (*b)))", LAMPS))
    assert d.step(extra=[["lamp", "L1", "on", "T"]]) == [["*a", 1]]


def test_a_test_and_the_empty_list_are_conditions_too():
    extra = "(concepts ((level ?n) :percepts ((level ?n))))"
    body = "(do-first ((level ?n) (do-first ((< ?n 3) (*a)) (() (*b)))))"
    d = Driver(body_program(body, extra))
    assert d.step(extra=[["level", 1]]) == [["*a"]]
    assert d.step(extra=[["level", 5]]) == [["*b"]]
    assert run("(do (wait ()) (*a))", [[]]) == ["a"]             # () is always true
    assert run("(do :while () (*a))", [[]]) == ["a"]


def errors(body: str) -> list[str]:
    text = PRELUDE + f"\n(skills ((never ?x) :percepts ((self ?x))\n :body {body}))"
    with pytest.raises(ProgramError) as info:
        load_program_text(text, "c.tlp")
    return [str(d) for d in info.value.errors]


LINE = PRELUDE.count("\n") + 3   # the line of :body
EXPECTED = ("one condition such as (lamp-on L1), a list of conditions such as "
            "((lamp-on L1) (clear ?x)), or () for always true")


def test_anything_else_is_refused_naming_the_forms_expected():
    assert errors("(do-first (flag (*a)))") == [
        f"c.tlp:{LINE}:18: each alternative of (do-first ...) is (CONDS STEP), where CONDS "
        f"is {EXPECTED}; got (flag (*a))"]
    assert errors("(do :while flag (*a))") == [
        f"c.tlp:{LINE}:12: :while in (do ...) needs CONDS after it: {EXPECTED}; got flag"]
    assert errors("(do-first (((flag x) flag) (*a)))") == [
        f"c.tlp:{LINE}:29: the conditions of an alternative of (do-first ...): in a list of "
        "conditions each one is a condition such as (lamp-on L1) or (not (clear ?x)), got "
        f"flag (CONDS is {EXPECTED})"]
    assert errors("(do (wait flag) (*a))")[0] == (
        f"c.tlp:{LINE}:18: (wait ...): expected CONDS, {EXPECTED}; got flag")
    assert errors("(do-best ((flag x) :utility 1 (*a)) (((flag x) ()) :utility 2 (*b)))")[0] \
        .endswith(f"got () (CONDS is {EXPECTED})")


@settings(max_examples=40, deadline=None)
@given(where=st.sampled_from(sorted(CONSTRUCTS)), neg=st.booleans(),
       flags=st.lists(st.lists(st.sampled_from(["x", "y"]), max_size=2, unique=True),
                      min_size=1, max_size=8),
       seed=st.integers(0, 5))
def test_both_forms_give_the_same_trace_on_random_percepts(where, neg, flags, seed):
    lit = "(not (flag x))" if neg else "(flag x)"
    one = run(CONSTRUCTS[where].format(c=lit), flags, seed)
    listed = run(CONSTRUCTS[where].format(c=f"({lit})"), flags, seed)
    assert one == listed
