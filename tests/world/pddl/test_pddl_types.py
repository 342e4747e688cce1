"""The root type written out (world/pddl/type_list.py): a type declared under `object` and
again under another type (IPC storage), and `- object` closing a list, which the pddl package
refuses, are read as PDDL means them; every message keeps its line and column."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st
from pddl_helpers import write_problem

from world.errors import ConfigError
from world.pddl.files import load_domain, load_task
from world.pddl.task import uncommented
from world.pddl.type_list import single_types

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


def test_object_before_other_typed_names_is_still_refused_in_one_line(tmp_path):
    text = STORAGE.replace("(free ?a ?b - object)", "(free ?a - object ?b - hoist)")
    with pytest.raises(ConfigError) as caught:
        load_domain(write_problem(tmp_path, text, "d.pddl"))
    assert "\n" not in str(caught.value) and str(caught.value).startswith(str(tmp_path))


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
