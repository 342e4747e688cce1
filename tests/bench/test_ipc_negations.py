"""The independent replay (bench/ipc/strips.py) on domains with negative preconditions and
equality, which pyperplan's parser does not read (bench/ipc/negations.py rewrites them for it):
known good and bad plans, what it still cannot read, and random plans judged the same as by
the world's own PDDL semantics (world/pddl/semantics.py, a separate implementation on another
parser)."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bench.ipc import negations, strips
from world.pddl import semantics
from world.pddl.files import load_task

DOMAIN = """; rooms behind doors that may be locked
(define (domain doors)
  (:requirements :strips :typing :negative-preconditions :equality)
  (:types room key)
  (:predicates (at ?r - room) (locked ?r - room) (link ?a - room ?b - room)
               (holding ?k - key) (opens ?k - key ?r - room))
  (:action go
    :parameters (?a - room ?b - room)
    :precondition (and (at ?a) (link ?a ?b) (not (locked ?b)) (not (= ?a ?b)))
    :effect (and (not (at ?a)) (at ?b)))
  (:action unlock
    :parameters (?k - key ?r - room ?here - room)
    :precondition (and (holding ?k) (opens ?k ?r) (locked ?r) (at ?here) (link ?here ?r))
    :effect (not (locked ?r)))
  (:action swap
    :parameters (?k - key ?j - key)
    :precondition (and (holding ?k) (not (holding ?j)) (= ?k ?k))
    :effect (and (not (holding ?k)) (holding ?j))))
"""
PROBLEM = """(define (problem three) (:domain doors)
  (:objects a b c - room k1 k2 - key)
  (:init (at a) (locked b) (link a b) (link b c) (link a a) (link c b) (holding k2)
         (opens k1 b))
  (:goal (and (at c))))
"""
NEGATIVE_GOAL = PROBLEM.replace("(:goal (and (at c)))", "(:goal (and (not (holding k2)) (at a)))")
ROOMS, KEYS = ("a", "b", "c"), ("k1", "k2")


@pytest.fixture(scope="module", params=[PROBLEM, NEGATIVE_GOAL], ids=["goal", "negative-goal"])
def problem(request) -> str:
    return request.param


@pytest.fixture(scope="module")
def files(tmp_path_factory, problem) -> tuple[Path, Path]:
    here = tmp_path_factory.mktemp("doors")
    (here / "domain.pddl").write_text(DOMAIN)
    (here / "problem.pddl").write_text(problem)
    return here / "domain.pddl", here / "problem.pddl"


def _files(tmp_path: Path, problem: str) -> tuple[Path, Path]:
    (tmp_path / "domain.pddl").write_text(DOMAIN)
    (tmp_path / "problem.pddl").write_text(problem)
    return tmp_path / "domain.pddl", tmp_path / "problem.pddl"


def test_a_good_plan_through_negative_preconditions_is_valid(tmp_path) -> None:
    plan = [("swap", "k2", "k1"), ("unlock", "k1", "b", "a"), ("go", "a", "b"), ("go", "b", "c")]
    assert strips.verify(*_files(tmp_path, PROBLEM), plan) == strips.Verdict(True, 4)


def test_a_negative_goal_is_checked_at_the_end(tmp_path) -> None:
    files = _files(tmp_path, NEGATIVE_GOAL)
    assert strips.verify(*files, [("swap", "k2", "k1")]) == strips.Verdict(True, 1)
    assert strips.verify(*files, []).reason == "the goal's (not (holding k2)) false at the end"


@pytest.mark.parametrize("plan, reason", [
    ([("go", "a", "b")], "step 1: (go a b): precondition (not (locked b)) is false"),
    ([("go", "a", "a")], "step 1: (go a a): precondition (not (= a a)) is false"),
    ([("swap", "k2", "k2")], "step 1: (swap k2 k2): precondition (not (holding k2)) is false"),
    ([("swap", "k2", "k1"), ("unlock", "k1", "b", "a")], "the goal's (at c) false at the end"),
])
def test_a_bad_plan_is_denied_naming_the_negative_literal(tmp_path, plan, reason) -> None:
    verdict = strips.verify(*_files(tmp_path, PROBLEM), plan)
    assert verdict.read and not verdict.valid
    assert verdict.reason.startswith(reason)


def test_a_domain_without_negations_is_left_as_it_is() -> None:
    plain = DOMAIN.replace("(not (locked ?b)) (not (= ?a ?b))", "").replace(
        "(not (holding ?j)) (= ?k ?k)", "").replace("(and (not (at ?a)) (at ?b))", "(at ?b)")
    plain = plain.replace("(not (locked ?r))", "(at ?r)").replace(
        "(and (not (holding ?k)) (holding ?j))", "(holding ?j)")
    assert negations.positive(plain, PROBLEM) == (plain, PROBLEM)


def test_what_pyperplan_cannot_read_is_no_verdict_either_way(tmp_path) -> None:
    forall = DOMAIN.replace("(not (locked ?b))", "(forall (?k - key) (holding ?k))")
    (tmp_path / "domain.pddl").write_text(forall)
    (tmp_path / "problem.pddl").write_text(PROBLEM)
    verdict = strips.verify(tmp_path / "domain.pddl", tmp_path / "problem.pddl", [])
    assert not verdict.read and not verdict.valid
    assert verdict.reason.startswith("the replay cannot read this task (SemanticError")


STEPS = st.one_of(
    st.tuples(st.just("go"), st.sampled_from(ROOMS), st.sampled_from(ROOMS)),
    st.tuples(st.just("unlock"), st.sampled_from(KEYS), st.sampled_from(ROOMS),
              st.sampled_from(ROOMS)),
    st.tuples(st.just("swap"), st.sampled_from(KEYS), st.sampled_from(KEYS)))


@settings(max_examples=200, deadline=None)
@given(plan=st.lists(STEPS, max_size=8))
def test_random_plans_are_judged_as_the_worlds_semantics_judge_them(files, plan) -> None:
    task, replay = load_task(*files), strips.load(*files)
    state, legal = task.init, True
    for step in plan:
        state, why = semantics.apply(task, state, list(step))
        if why:
            legal = False
            break
    reached = legal and not semantics.satisfied(task.goal, state)
    verdict = strips.check(replay, plan)
    assert verdict.valid == reached
    assert ("precondition" in verdict.reason) == (not legal)
