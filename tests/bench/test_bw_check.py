"""The planning bench's own check of a teleo run (bench/planning/bw_strips.py,
bench/planning/bw_check.py): the STRIPS rules agree with the pymunk Blocks World on random action
sequences; a run with an illegal action, a goal left false, a summary claiming a false goal or a
world that is not the replayed state is not solved."""

from __future__ import annotations

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bench.planning import bw_strips
from bench.planning.bw_check import check, world_on
from bench.planning.bw_problems import Problem, problem
from bench.planning.bw_teleo import TeleoRun
from world.domain import get_domain


def world_after(p: Problem, actions: list[list]) -> dict:
    """The real world's final snapshot after ``actions``, one a cycle."""
    world = get_domain("blocks").create({"towers": [list(t) for t in p.start]}, 0, ["ME"])
    for a in actions:
        outcome = world.apply_actions("ME", [a])[0]
        assert outcome["status"] == "done", outcome
        world.step()
    return world.snapshot_dict()


def random_walk(p: Problem, rng: random.Random, length: int) -> list[tuple[str, ...]]:
    """``length`` legal steps drawn at random from the start of ``p``."""
    state, steps = bw_strips.initial(p.start), []
    blocks = sorted(b for t in p.start for b in t)
    for _ in range(length):
        step, state = rng.choice(list(bw_strips.successors(state, blocks)))
        steps.append(step)
    return steps


def on_pairs(state: bw_strips.State) -> frozenset:
    return frozenset((f[1], f[2]) for f in state if f[0] == "on")


@settings(max_examples=15, deadline=None)
@given(st.integers(2, 6), st.integers(0, 10**6), st.integers(0, 12))
def test_strips_rules_and_the_pymunk_world_agree_on_random_legal_walks(n, seed, length):
    p = problem(n, seed)
    steps = random_walk(p, random.Random(seed), length)
    final = world_after(p, [bw_strips.to_teleo(s) for s in steps])
    assert world_on(final) == on_pairs(bw_strips.replay(p.start, steps))


def test_replay_names_the_first_illegal_step():
    towers = (("B1", "B2"), ("B3",))
    with pytest.raises(bw_strips.Illegal, match=r"step 2: \(stack B3 B1\): precondition "
                                                r"\(clear B1\) is false"):      # B2 is on B1
        bw_strips.replay(towers, [("pick-up", "B3"), ("stack", "B3", "B1")])
    with pytest.raises(bw_strips.Illegal, match=r"step 1: .*precondition \(on B1 B2\)"):
        bw_strips.replay(towers, [("unstack", "B1", "B2")])
    with pytest.raises(bw_strips.Illegal, match="not the table"):
        bw_strips.from_teleo(["*putdown", "B2", "B3"])


def run_of(p: Problem, steps: list[tuple[str, ...]], claims: list[tuple[str, str]],
           world: bool = True) -> TeleoRun:
    actions = [[bw_strips.to_teleo(s)] for s in steps] + [[]]
    return TeleoRun(actions=actions, solving=[False] * len(actions),
                    summary_goals=[{"goal": g, "status": s, "note": ""} for g, s in claims],
                    final=world_after(p, [a[0] for a in actions if a]) if world else {})


P = Problem(3, 0, (("B1", "B2"), ("B3",)), (("B3", "B2", "B1"),))


def test_a_plan_that_reaches_the_goal_is_solved_and_counted():
    plan = bw_strips.shortest_plan(P.start, P.goal())
    v = check(P, run_of(P, plan, [("(goal-state)", "achieved")]), 1)
    assert (v.solved, v.invalid, v.actions, v.cycles) == (True, "", len(plan), len(plan))


def test_an_illegal_action_is_not_a_solve_even_if_the_goal_ends_true():
    plan = bw_strips.shortest_plan(P.start, P.goal())
    run = run_of(P, plan, [("(goal-state)", "achieved")], world=False)
    run.actions.insert(0, [["*stack", "B3", "B2"]])          # B3 is not held
    v = check(P, run, 1)
    assert not v.solved and "cycle 0: (stack B3 B2): precondition (holding B3)" in v.invalid


def test_a_summary_claiming_a_false_goal_fails_the_check():
    v = check(P, run_of(P, [("unstack", "B2", "B1")], [("(on B2 B3)", "achieved"),
                                                         ("(on B3 B1)", "failed")]), 2)
    assert not v.solved and "the summary says (on B2 B3) achieved; it is false" in v.invalid
    assert v.unfinished == ["(on B3 B1): failed"]             # failed, and no reason given


def test_a_goal_left_false_is_not_solved_and_takes_the_limit():
    v = check(P, run_of(P, [("unstack", "B2", "B1")], [("(goal-state)", "impasse")]), 1)
    assert (v.solved, v.invalid, v.cycles, v.unfinished) == (
        False, "", 50, ["(goal-state): impasse"])


def test_a_world_that_is_not_the_replayed_state_fails_the_check():
    plan = bw_strips.shortest_plan(P.start, P.goal())
    run = run_of(P, plan, [("(goal-state)", "achieved")])
    run.final = world_after(P, [])                            # as if no action had been done
    v = check(P, run, 1)
    assert not v.solved and "the world's final state differs" in v.invalid


def test_an_action_the_world_refused_is_left_out_of_the_replay_and_counted():
    plan = bw_strips.shortest_plan(P.start, P.goal())
    assert plan[0] == ("unstack", "B2", "B1")                # then the hand holds B2
    run = run_of(P, plan, [("(goal-state)", "achieved")])
    run.actions[1:1] = [[["*pickup", "B3", "T"]],             # STRIPS: the hand is not empty
                        [["*stack", "B2", "B1"]]]             # STRIPS allows it
    run.solving += [False, False]
    run.refused = [0, 1, 1] + [0] * (len(run.actions) - 3)    # the world refused both
    v = check(P, run, 1)
    assert (v.solved, v.invalid, v.actions, v.refused, v.refused_legal) == (
        True, "", len(plan), 2, 1)
    run.refused = [0] * len(run.actions)                      # had the world done them
    assert "cycle 1: (pick-up B3): precondition" in check(P, run, 1).invalid


def test_refusals_are_read_from_the_growth_of_the_failed_counter_along_the_trace():
    from bench.planning.bw_teleo import refusals

    lines = [f'{{"cycle": {c}, "counters": {{"ME": {{"actions_failed": {f}}}}}}}'
             for c, f in enumerate([0, 0, 1, 1])]
    assert refusals(lines, {"counters": {"ME": {"actions_failed": 2}}}) == [0, 1, 0, 1]
