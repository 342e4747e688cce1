"""The solver's agenda and its search agree on what is pushed next (agents/lang/solving/
solver.py, ``_refocus``; search.py, ``next_push``): before dropping the conjunct a stack works
on, the agenda asks whether the search would push it straight back (a livelock). It asked
without the focus the search pushes by (the conjunct the executive's last path served), so
its answer could be about another decision than the next one; both now ask ``next_push``,
which is ``decide`` itself, with the focus."""

from __future__ import annotations

from dataclasses import replace

import pytest

from agents.lang import Engine, as_percepts
from agents.lang.core.store import PerceptIndex, store_of
from agents.lang.solving.search import advance, next_push
from agents.lang.solving.state import GoalStack, StackEntry
from agents.lang.solving.task import Task

from ..conftest import figure3_program
from ..test_blocks import percepts

GOAL = "(and (on A B) (on C D) (on E F))"


@pytest.fixture(scope="module")
def task() -> Task:
    engine = Engine(figure3_program())
    index = PerceptIndex(as_percepts(percepts({b: "T" for b in "ABCDEF"})))
    return Task(engine.program, index, store_of(engine.infer(index)))


@pytest.mark.parametrize("focus, pushed", [("", "(on A B)"), ("(on C D)", "(on C D)"),
                                           ("(on E F)", "(on E F)")])
def test_the_prediction_is_the_push_the_search_makes_with_the_same_focus(task, focus, pushed):
    """Three free towers, none a single action away: the one the executive's path served
    goes on, else the first written; the prediction follows the focus as the search does."""
    entry = StackEntry(GOAL, "goal g1 in impasse")
    step = advance(task, GoalStack("g1", (entry,)), lambda goal, keep, made: None, focus)
    assert [e.goal for e in step.stack.entries] == [GOAL, pushed]
    assert next_push(task, entry, [GOAL], focus) == pushed


def test_a_conjunct_pushed_its_last_time_is_not_predicted_again(task):
    """The prediction sees the pushes the search counts: (on C D) pushed twice already (a
    circle) is not pushed again whatever the focus."""
    entry = StackEntry(GOAL, "goal g1 in impasse")
    none = lambda goal, keep, made: None   # noqa: E731 (no path: the search decides)
    chosen = advance(task, GoalStack("g1", (entry,)), none).stack.entries[0]
    twice = replace(chosen, pushes=("(on C D)", "(on C D)"))
    assert next_push(task, twice, [GOAL], "(on C D)") == "(on A B)"
