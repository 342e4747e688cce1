"""Random Blocks World problems nobody picked (issue 22): start and goal states of up to 6
blocks drawn uniformly (tests/lang/solving/blocksworld.py), the goal the goal state's (on X Y)
facts, run by the pure engine against the real pymunk Blocks World, every run replayed under
STRIPS rules from the start state:
* as one conjunction, the goal holds within 10 n + 20 cycles and the replayed state satisfies
  it, and the run never comes back to a state it left;
* skills learned on one problem solve that problem and any other that is solved without them;
* as a priority list (any order), every goal ends satisfied or failed with its reason within
  10 n + 20 cycles, none still active or waiting."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, load_program

from ..conftest import BLOCKS
from .blocksworld import conjunction, on_facts, random_state, run

NAMES = [f"B{i}" for i in range(1, 7)]
ENGINE = Engine(load_program(BLOCKS))


@st.composite
def problems(draw, most: int = 6):
    """(start towers, goal facts in a random order) over 2..most blocks; a goal state with no
    block on another (nothing to achieve) is drawn again."""
    rnd = draw(st.randoms(use_true_random=False))
    names = NAMES[:draw(st.integers(2, most))]
    start, facts = random_state(rnd, names), []
    while not facts:
        facts = on_facts(random_state(rnd, names))
    rnd.shuffle(facts)
    return start, facts


def _limit(start) -> int:
    return 10 * sum(len(t) for t in start) + 20


def _returns(keys: list, pursued: list | None = None) -> int:
    """How often the replayed run comes back to a state it had left; with ``pursued`` (the
    goal acting at each cycle), only a return while pursuing the goal pursued when the state
    was last seen (issue 22: an agent that "returns to a situation it has already been in
    while pursuing the same goal"; a lower goal that happens to undo what a failed higher
    goal began goes round no circle)."""
    seen: dict = {}
    back = 0
    for i, k in enumerate(keys):
        if k in seen and any(keys[j] != k for j in range(seen[k], i)) \
                and (pursued is None or pursued[i] == pursued[seen[k]]):
            back += 1
        seen[k] = i
    return back


def _acting(statuses: list[dict[str, str]]) -> list[str | None]:
    """The goal active at each cycle (the first in the list), or None."""
    return [next((g for g, s in row.items() if s == "active"), None) for row in statuses]


def _solved(start, facts, learned: tuple[str, ...] = ()):
    out = run(ENGINE, start, [(conjunction(facts), 1)], _limit(start), learned)
    return out, out.replay.holds(facts) and out.statuses[-1]["g1"] == "satisfied"


@settings(max_examples=60, deadline=None)
@given(problems())
def test_a_conjunction_is_achieved_and_the_replayed_state_satisfies_it(problem):
    start, facts = problem
    out, solved = _solved(start, facts)
    assert solved, (start, facts, out.notes[-1])
    assert len(out.actions) <= _limit(start)
    assert _returns(out.keys) == 0, (start, facts, out.plan)


@settings(max_examples=25, deadline=None)
@given(problems(), problems())
def test_learned_skills_solve_whatever_was_solved_without_them(first, other):
    learned = _solved(*first)[0].state.learned
    for start, facts in (first, other):
        fresh, solved = _solved(start, facts)
        again, solved_again = _solved(start, facts, learned)
        assert solved_again or not solved, (start, facts, learned, again.notes[-1])
        assert _returns(again.keys) == 0, (start, facts, again.plan)


@settings(max_examples=50, deadline=None)
@given(problems())
def test_a_priority_list_ends_with_every_goal_satisfied_or_failed(problem):
    """One goal per fact, in the drawn order (a tower top-down or any other): a lower goal may
    not undo a higher one that holds, so some fail, naming why; none goes on for ever, and
    every goal reported satisfied holds in the replayed state at the end."""
    start, facts = problem
    goals = [(f"(on {a} {b})", k + 1) for k, (a, b) in enumerate(facts)]
    out = run(ENGINE, start, goals, _limit(start))
    final = out.statuses[-1]
    assert len(out.actions) < _limit(start) or set(final.values()) <= {"satisfied", "failed"}
    assert set(final.values()) <= {"satisfied", "failed"}, (start, facts, final)
    for k, (a, b) in enumerate(facts):
        gid = f"g{k + 1}"
        if final[gid] == "failed":
            assert out.notes[-1][gid].startswith(f"(on {a} {b}) cannot be achieved"), \
                out.notes[-1][gid]
        else:
            assert out.replay.under.get(a) == b, (start, facts, gid)
    assert _returns(out.keys, _acting(out.statuses)) == 0, (start, facts, out.plan)


def test_a_return_counts_only_while_the_same_goal_is_pursued():
    """The counter of the property above: g3 lifts B4 and fails, g5 later holds B4 again."""
    keys = ["a", "b", "c", "b"]
    assert _returns(keys) == 1
    assert _returns(keys, [None, "g3", "g4", "g5"]) == 0
    assert _returns(keys, [None, "g3", "g4", "g3"]) == 1
