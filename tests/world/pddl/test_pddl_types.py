"""The root type written out (world/pddl/type_list.py): a type declared under `object` and
again under another type (IPC storage), `- object` closing a list, `object` declared as a type
and `- object` before other typed names (IPC tidybot), which the pddl package refuses, are
read as PDDL means them; every message keeps its line and column."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st
from pddl_helpers import write_problem

from world.errors import ConfigError
from world.pddl.costs import form_end
from world.pddl.files import load_domain, load_task
from world.pddl.semantics import apply
from world.pddl.task import uncommented
from world.pddl.type_list import ALIAS, root_alias, single_types

STORAGE = """(define (domain store)
(:requirements :typing)
(:types hoist surface place area - object
        depot - place
        storearea - area
        area crate - surface)
(:predicates (at ?h - hoist ?a - storearea) (on ?c - crate ?s - surface)
             (free ?a ?b - object))
(:action lift
  :parameters (?h - hoist ?c - crate ?a - storearea)
  :precondition (and (at ?h ?a) (on ?c ?a))
  :effect (not (on ?c ?a))))
"""
PROBLEM = """(define (problem p) (:domain store)
(:objects h1 - hoist c1 - crate s1 - storearea d1 - depot)
(:init (at h1 s1) (on c1 s1) (free h1 d1))
(:goal (and (free h1 d1))))
"""


def test_a_type_declared_under_the_root_and_under_another_keeps_the_other(tmp_path):
    model = load_domain(write_problem(tmp_path, STORAGE, "d.pddl"))
    assert model.ancestors("storearea") == ("storearea", "area", "surface", "object")
    assert model.ancestors("depot") == ("depot", "place", "object")


def test_object_closing_a_list_is_the_root_type(tmp_path):
    domain = write_problem(tmp_path, STORAGE, "d.pddl")
    model = load_domain(domain)
    assert dict(model.predicates)["free"] == (("?a", ("object",)), ("?b", ("object",)))
    task = load_task(domain, write_problem(tmp_path, PROBLEM))
    assert ("on", "c1", "s1") in task.init   # a storearea is a surface: the crate stands on it


def test_object_before_other_typed_names_is_the_root_type(tmp_path):
    text = STORAGE.replace("(free ?a ?b - object)", "(free ?a - object ?b - hoist)")
    model = load_domain(write_problem(tmp_path, text, "d.pddl"))
    assert dict(model.predicates)["free"] == (("?a", ("object",)), ("?b", ("hoist",)))
    assert ALIAS not in {t for t, _ in model.types} | {p for _, p in model.types}


TIDY = """(define (domain tidy)
  (:requirements :strips :typing)
  (:types robot cart object)
  (:predicates (holding ?r - robot ?o - object) (free ?r - robot) (at ?o - object))
  (:action grasp
   :parameters (?o - object ?r - robot)
   :precondition (and (free ?r) (at ?o))
   :effect (and (holding ?r ?o) (not (free ?r)) (not (at ?o)))))
"""
TIDY_PROBLEM = """(define (problem t1) (:domain tidy)
  (:objects object0 - object r1 - robot c1 - cart)
  (:init (free r1) (at object0) (at c1))
  (:goal (and (holding r1 object0))))
"""


def test_object_declared_as_a_type_is_the_root(tmp_path):
    """IPC tidybot declares `object` among its types and writes `?o - object ?r - robot`: the
    root, so ?o admits every object, a cart too, as PDDL says."""
    domain = write_problem(tmp_path, TIDY, "d.pddl")
    model = load_domain(domain)
    assert sorted(model.types) == [("cart", "object"), ("robot", "object")]
    assert model.operator("grasp").params == (("?o", ("object",)), ("?r", ("robot",)))
    task = load_task(domain, write_problem(tmp_path, TIDY_PROBLEM))
    assert dict(task.objects) == {"object0": "object", "r1": "robot", "c1": "cart"}
    state = frozenset(task.init)
    after, reason = apply(task, state, ["grasp", "c1", "r1"])
    assert reason == "" and ("holding", "r1", "c1") in after
    _, reason = apply(task, state, ["grasp", "r1", "c1"])
    assert "c1" in reason   # a cart is no robot


def test_the_root_declared_by_the_reader_keeps_later_positions(tmp_path):
    """`- object` before other names with no `object` among the types: the reader declares
    its alias at the end of the type list; a later syntax error keeps its line and column."""
    text = TIDY.replace("(:types robot cart object)", "(:types robot cart)") \
        .replace(":effect", ":efect")
    with pytest.raises(ConfigError) as caught:
        load_domain(write_problem(tmp_path, text, "d.pddl"))
    line = next(k for k, t in enumerate(text.splitlines(), 1) if ":efect" in t)
    col = text.splitlines()[line - 1].index(":efect") + 1
    assert f"d.pddl:{line}:{col}: pddl: syntax error" in str(caught.value)
    fixed = load_domain(write_problem(tmp_path, text.replace(":efect", ":effect"), "e.pddl"))
    assert fixed.operator("grasp").params[0] == ("?o", ("object",))


def test_a_domain_naming_the_alias_is_left_to_the_parser(tmp_path):
    text = TIDY.replace("cart object)", f"cart object {ALIAS})")
    with pytest.raises(ConfigError, match=r"d\.pddl:3:\d+: pddl: .*object"):
        load_domain(write_problem(tmp_path, text, "d.pddl"))


def test_a_later_error_keeps_its_line_and_column(tmp_path):
    def error(text: str) -> str:
        with pytest.raises(ConfigError) as caught:
            load_domain(write_problem(tmp_path, text, "d.pddl"))
        return str(caught.value)

    bad = STORAGE.replace(":effect", ":efect")   # the library's syntax error, line 12
    by_hand = bad.replace("place area - object", "place      - object")   # blanked already
    assert error(bad) == error(by_hand)
    assert ":12:" in error(bad) and "syntax error" in error(bad)


NAMES = st.sampled_from(["a", "b", "c", "area", "object", "-", "(", ")", "?x", "\n", "  "])


@given(st.lists(NAMES, max_size=40))
def test_only_blanks_are_written_and_the_length_is_kept(tokens):
    code = uncommented("(define (domain d) (:types " + " ".join(tokens) + ") (:predicates (p "
                       + " ".join(tokens) + ")))")
    out = single_types(code)
    assert len(out) == len(code)
    assert all(new == old or new == " " for new, old in zip(out, code, strict=True))


@given(st.lists(NAMES, max_size=40), st.lists(NAMES, max_size=20))
def test_the_alias_moves_no_line_and_no_column_but_at_the_type_list_end(types, params):
    code = uncommented("(define (domain d)\n(:types " + " ".join(types) + ")\n(:predicates (p "
                       + " ".join(params) + ")))")
    before = single_types(code)
    out = root_alias(before)
    end = before[:form_end(before, before.index("(:types"))].count("\n")   # the list's end
    assert out.count("\n") == code.count("\n")
    for k, (new, old) in enumerate(zip(out.splitlines(), before.splitlines(), strict=True)):
        if k != end:
            assert len(new) == len(old)
            assert new == old or new.replace(ALIAS, "object") == old
