"""The problem solver's state is part of EngineState: it survives JSON (what a restarted
executive reads back) exactly, a run continued from the round-tripped state decides exactly
as the uninterrupted one, and the same problem gives the same stacks and skills in any
process (no dependence on string hashing)."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, EngineState, StateError
from agents.lang.solving.state import SolverState

from ..conftest import figure3_program
from ..test_blocks import act, percepts
from ..test_determinism import under_hash_seeds
from ..test_properties import towers

PROGRAM = figure3_program()


def _through_json(state: EngineState) -> EngineState:
    return EngineState.from_dict(json.loads(json.dumps(state.to_dict())))


def _run_with_restarts(support: dict, goal: str, cycles: int) -> list[int]:
    """Run ``goal`` twice side by side: one engine throughout, and a fresh engine each cycle
    from the state read back from JSON; assert they agree; return the stack depth per cycle."""
    steady = Engine(PROGRAM)
    state = steady.add_goal(steady.remove_goal(steady.initial_state(), "p1"), goal, 0, "g1")
    restarted = state
    holding, depths = None, []
    for _ in range(cycles):
        ps = percepts(support, holding)
        got = steady.cycle(state, ps)
        again = Engine(PROGRAM).cycle(_through_json(restarted), ps)
        assert again.decision.to_dict() == got.decision.to_dict()
        assert again.state == got.state
        assert _through_json(got.state) == got.state
        assert SolverState.from_dict(got.state.solver.to_dict()) == got.state.solver
        state, restarted = got.state, again.state
        depths.append(sum(len(s.entries) for s in state.solver.stacks))
        for a in got.decision.actions:
            support, holding = act(support, holding, a.to_list())
    return depths


def test_figure3_state_round_trips_and_a_restart_changes_nothing():
    depths = _run_with_restarts({"A": "T", "B": "A", "C": "B"}, "(clear A)", 6)
    assert depths == [2, 3, 3, 1, 0, 0]


def test_a_backtracking_search_round_trips_mid_problem():
    """(above A A): the search goes five levels down (through (on A B) and (above B A)),
    backtracks and fails. ((on A A) no longer serves: it fails at once, its start
    contradicting itself, issue 31.)"""
    depths = _run_with_restarts({"A": "T", "B": "A"}, "(above A A)", 24)
    assert max(depths) == 6 and 2 in depths[depths.index(6):] and depths[-1] == 0


@st.composite
def problems(draw):
    """A random tower world (hand empty) and a goal over its blocks."""
    support, _ = draw(towers().filter(lambda t: len(t[0]) >= 2))
    x, y = draw(st.permutations(sorted(support)))[:2]
    goal = draw(st.sampled_from([f"(clear {x})", f"(on {x} {y})", f"(ontable {x} T)",
                                 f"(holding {x})"]))
    return support, goal


@settings(max_examples=15, deadline=None)
@given(problems())
def test_any_problem_state_round_trips_every_cycle(problem):
    support, goal = problem
    _run_with_restarts(support, goal, 6)


def test_a_malformed_solver_state_is_refused_naming_the_shape():
    good = Engine(PROGRAM).initial_state().to_dict()
    with pytest.raises(StateError, match="bad shape"):
        EngineState.from_dict({**good, "solver": {"stacks": [{"goal_id": "p1"}]}})


SCRIPT = """
from agents.lang import Engine, load_program
from tests.lang.test_blocks import run
engine = Engine(load_program("programs/blocks.tlp"))
state = engine.add_goal(engine.initial_state(), "(holding A)", priority=0)
trace, _, _, state = run(engine, state, {"B": "T", "A": "B", "C": "A", "D": "T"}, cycles=9)
for decision, _ in trace:
    print(decision.explain())
print(state.learned)
"""


def test_same_stacks_and_skills_under_different_hash_seeds():
    outputs = under_hash_seeds(SCRIPT)
    assert outputs[0] == outputs[1] == outputs[2]
    assert "goal stack of g1" in outputs[0] and "learned skill (holding ?b1)" in outputs[0]
