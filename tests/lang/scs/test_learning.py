"""Discount factors of do-best alternatives (seed 002, Appendix A, "Learning"): initially 1,
multiplied with the utility, updated after each execution by the reinforcement rule of
agents/lang/scs/learning.py (d <- d + 0.3 (r - d); r = 0 on failure, 1 or the :reward on
success)."""

from __future__ import annotations

import pytest

from agents.lang.scs.learning import LEARNING_RATE, reinforce, reward_value
from tests.lang.scs.drive import Driver, body_program, failing

CHOICE = "(do-best (() :utility 10 (*a)) (() :utility 6 (*b)))"


def factors(d: Driver) -> dict:
    return {c["label"].split()[0]: c["factor"] for c in d.scs["choices"]}


def test_the_rule_moves_the_factor_toward_the_measured_result():
    assert reinforce(1.0, 0.0) == pytest.approx(1 - LEARNING_RATE)
    assert reinforce(0.49, 1.0) == pytest.approx(0.49 + LEARNING_RATE * 0.51)
    assert reinforce(0.0, 0.0) == 0.0 and reinforce(1.0, 1.0) == 1.0
    assert reward_value(3) == 1.0 and reward_value(-2) == 0.0 and reward_value("T") == 0.0


def test_an_alternative_with_higher_static_utility_that_keeps_failing_loses():
    """10 x d(a) against 6 x d(b): a is tried first twice, fails each time (and b, tried
    next, succeeds); after two failures d(a) = 0.49 and 4.9 < 6, so b is chosen first."""
    d = Driver(body_program(CHOICE), policy=failing("a"))
    assert d.run(8) == ["a", "b", "a", "b", "b", "b", "b", "b"]
    assert factors(d) == {"(*a)": pytest.approx(0.49), "(*b)": 1.0}
    a = next(c for c in d.scs["choices"] if c["label"].startswith("(*a)"))
    assert (a["chosen"], a["succeeded"], a["failed"]) == (2, 0, 2)


def test_without_failures_the_higher_utility_keeps_winning():
    d = Driver(body_program(CHOICE))
    assert d.run(4) == ["a", "a", "a", "a"]
    assert factors(d) == {"(*a)": 1.0}


def test_a_reward_expression_over_the_percepts_after_the_step_is_the_result():
    """The alternative succeeds but the reward (read from the percepts of the next cycle)
    is 0.2, so its factor falls toward 0.2 (0.76, 0.592) and the other alternative (7)
    takes over once 10 d < 7."""
    extra = "(concepts ((score ?s) :percepts ((score ?s))))"
    body = ("(do-best (((score ?s)) :utility 10 :reward (/ ?s 10) (*a))"
            " (() :utility 7 (*b)))")
    d = Driver(body_program(body, extra))
    out = [d.step(extra=[["score", 2]]) for _ in range(3)]
    assert out == [[["*a"]], [["*a"]], [["*b"]]]
    assert factors(d)["(*a)"] == pytest.approx(reinforce(reinforce(1.0, 0.2), 0.2))


def test_an_abandoned_alternative_is_not_reinforced():
    body = "(do-best (((flag x)) :utility 10 (do (*a) (*b) (*e))) (() :utility 1 (*c)))"
    d = Driver(body_program(body))
    assert d.run(3, lambda k: ["x"] if k < 2 else []) == ["a", "b", "c"]
    first = next(c for c in d.scs["choices"] if c["label"].startswith("(do"))
    # x failed before (do ...) ended (it would go on with (*e)): chosen, but neither a
    # success nor a failure
    assert (first["factor"], first["chosen"], first["succeeded"], first["failed"]) == \
        (1.0, 1, 0, 0)


def test_the_factors_are_state_that_survives_a_restart(tmp_path):
    import json

    from agents.lang import EngineState
    d = Driver(body_program(CHOICE), policy=failing("a"))
    d.run(4)
    path = tmp_path / "state.json"
    path.write_text(json.dumps(d.state.to_dict()))
    again = Driver(body_program(CHOICE), policy=failing("a"))
    again.state = EngineState.from_dict(json.loads(path.read_text()))
    again.outcomes = d.outcomes
    assert again.run(2) == ["b", "b"]
    assert "do-best discount factors:" in again.result.decision.explain()
    assert "never#1@0: 0.490 (chosen 2, succeeded 0, failed 2)  (*a)" in \
        again.result.decision.explain()
