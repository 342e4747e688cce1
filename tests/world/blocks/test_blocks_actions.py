"""Seed 000's four Blocks World actions: each done in one cycle, or refused with a reason that
names the agent, the action and what is wrong, changing nothing."""

from __future__ import annotations

import pytest
from blocks_helpers import act, blocks_seen, seen, settle, world


def test_unstack_lifts_a_clear_block_off_the_block_under_it():
    w = world([["A", "B", "C"]])
    assert act(w, "*unstack", "C", "B") == {"action": ["*unstack", "C", "B"], "status": "done",
                                            "reason": ""}
    assert seen(w)[1] == ["hand", "H1", "status", "C"]
    assert blocks_seen(w)["C"] == (99, 99, 2)


def test_pickup_lifts_a_clear_block_off_the_table():
    w = world([["A"], ["B"]])
    assert act(w, "*pickup", "B", "T")["status"] == "done"
    assert seen(w)[1] == ["hand", "H1", "status", "B"]


def test_putdown_sets_the_block_in_the_leftmost_free_column():
    w = world([["A", "B"], [], ["C"]])
    act(w, "*unstack", "B", "A")
    assert act(w, "*putdown", "B", "T")["status"] == "done"
    assert blocks_seen(w)["B"] == (3, 2, 2)      # column 1, x = 3 m, on the 2 m table
    assert seen(w)[1] == ["hand", "H1", "status", "empty"]


def test_stack_sets_the_block_centred_on_a_clear_block():
    w = world([["A"], ["B"]])
    act(w, "*pickup", "B", "T")
    assert act(w, "*stack", "B", "A")["status"] == "done"
    assert blocks_seen(w) == {"A": (0, 2, 2), "B": (0, 4, 2)}
    assert w.snapshot_dict()["counters"]["ME"] == {
        "actions_done": 2, "actions_failed": 0, "blocks_moved": 1, "blocks_dropped": 0}


REFUSALS = [
    # (towers, holding, action, reason)
    ([["A", "B", "C"]], None, ["*unstack", "B", "A"],
     "ME: (*unstack B A): B is not clear: C on it"),
    ([["A", "B"]], None, ["*unstack", "B", "C"], "C is an unknown block; blocks: A, B"),
    ([["A", "B"], ["C"]], None, ["*unstack", "B", "C"], "B is not on C: it is on A"),
    ([["A", "B"]], None, ["*unstack", "A", "T"], "T is the table, not a block"),
    ([["A"], ["B"]], "C", ["*unstack", "A", "T"], "T is the table, not a block"),
    ([["A", "B"]], "C", ["*unstack", "B", "A"], "the hand H1 is not empty: it holds C"),
    ([["A", "B"]], None, ["*pickup", "B", "T"], "ME: (*pickup B T): B is not on T: it is on A"),
    ([["A", "B"]], None, ["*pickup", "A", "T"], "A is not clear: B on it"),
    ([["A"]], "C", ["*pickup", "A", "T"], "the hand H1 is not empty: it holds C"),
    ([["A"]], None, ["*pickup", "A", "TABLE"], "TABLE is unknown; the table is T"),
    ([["A"], ["B"]], None, ["*pickup", "A", "B"], "B is a block, not the table; the table is T"),
    ([["A"]], None, ["*pickup", "Z", "T"], "Z is an unknown block; blocks: A"),
    ([["A"]], None, ["*putdown", "A", "T"], "the hand H1 is not holding A: it holds nothing"),
    ([["A"]], "C", ["*putdown", "A", "T"], "the hand H1 is not holding A: it holds C"),
    ([["A"]], "C", ["*putdown", "C", "A"], "A is a block, not the table; the table is T"),
    ([["A"]], "C", ["*stack", "A", "C"], "the hand H1 is not holding A: it holds C"),
    ([["A", "B"]], "C", ["*stack", "C", "A"], "ME: (*stack C A): A is not clear: B on it"),
    ([["A"]], "C", ["*stack", "C", "C"], "C cannot be stacked on itself"),
    ([["A"]], "C", ["*stack", "C", "T"], "T is the table, not a block"),
    ([["A"]], "C", ["*stack", "C"], "expected 2 arguments (*stack ?block ?to), got 1"),
    ([["A"]], None, ["*pickup", "A", "T", "now"], "expected 2 arguments (*pickup ?block ?table)"),
    ([["A"]], "C", ["*stack", "C", 3], "argument 2 ?to: expected a name, got 3"),
    ([["A"]], None, ["*fly-away", 3], "unknown action *fly-away; the Blocks World knows "
                                      "*pickup, *unstack, *putdown, *stack, *wait"),
    ([["A"]], None, [], "expected [name, arg, ...]"),
]


@pytest.mark.parametrize("towers, holding, action, reason", REFUSALS,
                         ids=[r[3][:40] for r in REFUSALS])
def test_a_refused_action_says_why_and_changes_nothing(towers, holding, action, reason):
    w = world(towers, **({"holding": {"ME": holding}} if holding else {}))
    before = w.snapshot_dict()
    [outcome] = w.apply_actions("ME", [action])
    assert outcome["status"] == "failed" and outcome["action"] == action
    assert reason in outcome["reason"] and outcome["reason"].startswith("ME: ")
    after = w.snapshot_dict()
    assert after["counters"]["ME"]["actions_failed"] == 1
    assert {**after, "counters": None} == {**before, "counters": None}


def test_no_free_place_on_a_full_table():
    w = world([["A"], ["B"]], table={"columns": 2}, holding={"ME": "C"})
    [outcome] = w.apply_actions("ME", [["*putdown", "C", "T"]])
    assert outcome["status"] == "failed"
    assert "no free place for C (width 2 m) on the table T: its 2 columns are taken" in \
        outcome["reason"]


def test_no_room_for_a_wide_block_beside_a_tower():
    w = world([["A"], ["B", "D"]], sizes={"C": [4.5, 1.0]}, holding={"ME": "C"})
    [outcome] = w.apply_actions("ME", [["*stack", "C", "A"]])
    assert outcome["status"] == "failed"
    assert "no room for C (width 4.5 m) on A: it would hit D" in outcome["reason"]
    w.step()
    assert act(w, "*stack", "C", "D")["status"] == "done"   # over A's top it fits
    assert w.snapshot_dict()["events"] == []               # and stands


def test_a_block_in_another_agents_hand_cannot_be_taken_or_stacked_on():
    w = world([["A"], ["B"]], agents=("ME", "YOU"), holding={"YOU": "C"})
    [outcome] = w.apply_actions("ME", [["*pickup", "C", "T"]])
    assert "C is held by YOU's hand H2" in outcome["reason"]
    w.step()                               # a refused action used the gripper's cycle too
    assert act(w, "*pickup", "A", "T")["status"] == "done"
    [outcome] = w.apply_actions("ME", [["*stack", "A", "C"]])
    assert "C is held by YOU's hand H2" in outcome["reason"]


def test_one_gripper_action_a_cycle_and_wait_is_always_done():
    w = world([["A"], ["B"]])
    first, second, wait = w.apply_actions("ME", [["*pickup", "A", "T"], ["*pickup", "B", "T"],
                                                 ["*wait"]])
    assert first["status"] == "done" and wait["status"] == "done"
    assert second["status"] == "failed"
    assert "the gripper H1 already acted this cycle: (*pickup A T)" in second["reason"]
    w.step()
    assert act(w, "*putdown", "A", "T")["status"] == "done"    # the next cycle it may act


def test_the_safe_action_keeps_the_held_block_and_moves_nothing():
    w = world([["A", "B"]], holding={"ME": "C"})
    assert w.safe_actions("ME") == [["*wait"]]
    before = seen(w)
    assert act(w, *w.safe_actions("ME")[0])["status"] == "done"
    assert seen(w) == before and seen(w)[1] == ["hand", "H1", "status", "C"]


def test_an_unknown_agent_and_a_non_list_are_refused_by_name():
    w = world()
    [outcome] = w.apply_actions("NOBODY", [["*pickup", "A", "T"]])
    assert outcome["status"] == "failed" and "unknown agent 'NOBODY'" in outcome["reason"]
    [outcome] = w.apply_actions("ME", "*pickup")        # type: ignore[arg-type]
    assert outcome["status"] == "failed" and "expected a list of actions" in outcome["reason"]


def test_nothing_is_stacked_on_a_moving_block_nor_lifted_in_mid_air():
    w = world([["A"], ["B", "C"]], holding={"ME": "D"})
    w.inject({"kind": "knock", "block": "A", "speed": 2.0})
    [outcome] = w.apply_actions("ME", [["*stack", "D", "A"]])
    assert "A does not stand still and flat: nothing can go on it" in outcome["reason"]
    w.step()
    settle(w, 6)
    act(w, "*stack", "D", "C")
    act(w, "*unstack", "D", "C")
    w.inject({"kind": "slip", "agent": "ME"})           # D drops from the gripper
    [outcome] = w.apply_actions("ME", [["*unstack", "D", "C"]])
    assert "D is not on C: it is on nothing (it is falling)" in outcome["reason"]
