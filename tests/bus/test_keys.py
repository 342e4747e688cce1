"""The key layout (docs/architecture.md, bus section) and its guards."""

from __future__ import annotations

import pytest

from bus import keys
from bus.errors import KeyFormatError


def test_layout_matches_the_contract():
    assert keys.world_state("r1") == "teleo/r1/world/state"
    assert keys.world_events("r1") == "teleo/r1/world/events"
    assert keys.percepts("r1", "ME") == "teleo/r1/agent/ME/percepts"
    assert keys.beliefs("r1", "ME") == "teleo/r1/agent/ME/beliefs"
    assert keys.actions("r1", "ME") == "teleo/r1/agent/ME/actions"
    assert keys.intention("r1", "ME") == "teleo/r1/agent/ME/intention"
    assert keys.goals("r1", "ME") == "teleo/r1/agent/ME/goals"
    assert keys.goal_list("r1", "ME") == "teleo/r1/agent/ME/goal-list"
    assert keys.stats("r1", "ME.inference") == "teleo/r1/stats/ME.inference"
    assert keys.proc("r1", "world") == "teleo/r1/proc/world"
    assert keys.run_all("r1") == "teleo/r1/**"


@pytest.mark.parametrize("bad", ["", "a/b", "a*", "$x", "@adm", "a b", "q?", "#"])
def test_names_that_are_not_one_chunk_are_rejected(bad):
    with pytest.raises(KeyFormatError, match="agent"):
        keys.percepts("r1", bad)


def test_kinds_allowed_per_key():
    assert keys.kind_of_key(keys.world_state("r")) == {"WorldState"}
    assert keys.kind_of_key(keys.actions("r", "ME")) == {"Actions"}
    assert keys.kind_of_key(keys.goals("r", "ME")) == {"GoalRequest", "GoalReply"}
    assert keys.kind_of_key(keys.goal_list("r", "ME")) == {"GoalList"}
    assert keys.kind_of_key(keys.stats("r", "world")) == {"ProcessStats"}
    assert keys.kind_of_key("other/thing/x/y") == frozenset()


def test_token_and_agent_parsing():
    assert keys.process_of_token("r1", keys.proc("r1", "ME.executive")) == "ME.executive"
    assert keys.process_of_token("r1", keys.proc("r2", "world")) is None
    assert keys.agent_of_key(keys.beliefs("r1", "ME")) == "ME"
    assert keys.agent_of_key(keys.world_state("r1")) is None


@pytest.mark.parametrize("expr, problem", [
    ("", "non-empty"),
    ("teleo//x", "empty chunk"),
    ("/teleo/x", "empty chunk"),
    ("teleo/x/", "empty chunk"),
    ("teleo/a*", "stands alone"),
    ("teleo/$", "only allowed in"),
    ("teleo/x?y", "may not appear"),
    ("teleo/**/**", "write '\\*\\*'"),
    ("teleo/**/*", "write '\\*/\\*\\*'"),
])
def test_key_expressions_zenoh_refuses_are_refused_saying_why(expr, problem):
    with pytest.raises(KeyFormatError, match=problem):
        keys.check_keyexpr(expr)


def test_the_key_expression_check_agrees_with_zenoh():
    """Every expression over a small alphabet: refused here exactly when zenoh refuses it."""
    import itertools

    import zenoh

    alphabet = ["a", "/", "*", "$", "#"]
    for n in range(1, 6):
        for letters in itertools.product(alphabet, repeat=n):
            expr = "".join(letters)
            try:
                zenoh.KeyExpr(expr)
                zenoh_ok = True
            except zenoh.ZError:
                zenoh_ok = False
            try:
                keys.check_keyexpr(expr)
                ours = True
            except KeyFormatError:
                ours = False
            assert ours == zenoh_ok, expr
