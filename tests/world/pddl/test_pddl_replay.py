"""Random action sequences keep the pddl world's state equal to an independent replay: the
same actions applied by pyperplan's own parser and grounding (a dev dependency, GPL, used only
in tests and benchmarks), an action the world refuses being one pyperplan's grounding has no
applicable operator for, and every refusal leaving the state unchanged."""

from __future__ import annotations

from itertools import product

from hypothesis import given, settings
from hypothesis import strategies as st
from pddl_helpers import BLOCKS, GRIPPER, world_of
from pyperplan.grounding import ground
from pyperplan.pddl.parser import Parser


def _reference(files):
    parser = Parser(str(files[0]), str(files[1]))
    task = ground(parser.parse_problem(parser.parse_domain()))
    return task, {op.name: op for op in task.operators}


def _candidates(world) -> list[list[str]]:
    """Every action of the domain's operators over every object (most of them ill-typed or
    inapplicable)."""
    objects = [o for o, _ in world.task.objects]
    return [[f"*{op.name}", *args] for op in world.task.domain.operators
            for args in product(objects, repeat=len(op.params))]


def _facts(world, relevant) -> frozenset[str]:
    return frozenset(f"({' '.join(a)})" for a in world.snapshot_dict()["atoms"]) & relevant


def _check(files, picks: list[tuple[bool, int]]) -> None:
    world = world_of(files)
    task, ops = _reference(files)
    state = task.initial_state
    actions = _candidates(world)
    for legal, k in picks:
        applicable = sorted(n for n, op in ops.items() if op.applicable(state))
        if legal and applicable:   # one the reference can apply: deeper states
            action = applicable[k % len(applicable)].strip("()").split()
            action[0] = f"*{action[0]}"
        else:                      # any name and objects: mostly ill-typed or inapplicable
            action = actions[k % len(actions)]
        before = world.snapshot_dict()["atoms"]
        [out] = world.apply_actions("ME", [action])
        world.step()
        op = ops.get(f"({' '.join([action[0][1:], *action[1:]])})")
        if op is not None and op.applicable(state):
            state = op.apply(state)
            assert out["status"] == "done", (action, out)
        else:
            assert out["status"] == "failed", action
            assert world.snapshot_dict()["atoms"] == before
        assert _facts(world, task.facts) == state
    assert world.goal_holds() == task.goal_reached(state)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.integers(min_value=0, max_value=10**6)),
                max_size=40))
def test_random_blocks_actions_match_a_replay(picks):
    _check(BLOCKS, picks)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.integers(min_value=0, max_value=10**6)),
                max_size=40))
def test_random_gripper_actions_match_a_replay(picks):
    _check(GRIPPER, picks)
