"""Scenario events and faults (`[[events]]`, `teleo event`): each kind done, and a bad event
refused with the reason, changing nothing."""

from __future__ import annotations

import pytest
from blocks_helpers import blocks_seen, settle, world

from world.blocks import DOMAIN, EVENT_KINDS


def test_the_domain_lists_its_event_kinds():
    assert DOMAIN.event_kinds == EVENT_KINDS == ("add", "remove", "knock", "slip")


def test_add_sets_a_new_block_in_the_leftmost_free_column_or_on_a_clear_block():
    w = world([["A", "B"]])
    assert w.inject({"kind": "add", "block": "D"})["status"] == "done"
    assert w.inject({"kind": "add", "block": "E", "on": "D", "size": [1.0, 1.0]})["status"] \
        == "done"
    assert w.inject({"kind": "add", "block": "F", "column": 5})["status"] == "done"
    w.step()       # the next snapshot reports them
    assert [(e["kind"], e["event"]["block"]) for e in w.snapshot_dict()["events"]] == [
        ("injected", "D"), ("injected", "E"), ("injected", "F")]
    settle(w, 2)
    seen = blocks_seen(w)
    assert (seen["D"], seen["E"], seen["F"]) == ((3, 2, 2), (3, 4, 1), (15, 2, 2))


def test_remove_takes_a_clear_block_away():
    w = world([["A", "B"]])
    assert w.inject({"kind": "remove", "block": "B"})["status"] == "done"
    w.step()
    assert set(blocks_seen(w)) == {"A"}


BAD = [
    ({"kind": "add", "block": "A"}, "block: expected a new block name, got 'A'"),
    ({"kind": "add", "block": "T"}, "expected a new block name, got 'T'"),
    ({"kind": "add", "block": "D", "on": "A"}, "on: A is not clear: B on it"),
    ({"kind": "add", "block": "D", "on": "Q"}, "block: expected one of ['A', 'B'], got 'Q'"),
    ({"kind": "add", "block": "D", "size": [0, 1]},
     "size[0]: expected a number in [0.25, 20], got 0"),
    ({"kind": "add", "block": "D", "size": [1]}, "size: expected [width, height] [m], got [1]"),
    ({"kind": "add", "block": "D", "size": [True, 1]}, "size[0]: expected a number in [0.25, 20]"),
    ({"kind": "add", "block": "D", "column": 0}, "no room for D at x 0 m: it would hit A"),
    ({"kind": "add", "block": "D", "column": 9}, "column: expected an integer in [0, 5], got 9"),
    ({"kind": "remove", "block": "A"}, "block A is not clear: B on it"),
    ({"kind": "knock", "block": "B", "speed": "fast"},
     "speed: expected a number in [-30, 30], got 'fast'"),
    ({"kind": "knock", "block": "B", "speed": 1e308},
     "speed: expected a number in [-30, 30], got 1e+308"),
    ({"kind": "add", "block": "D", "offset": -1e200},
     "offset: expected a number in [-20, 20], got -1e+200"),
    ({"kind": "knock"}, "block: missing; expected a block name"),
    ({"kind": "knock", "block": ["B"]}, "block: expected a block name, got ['B']"),
    ({"kind": "slip", "agent": "ME"}, "ME's hand H1 holds nothing to drop"),
    ({"kind": "slip", "agent": "YOU"}, "agent: expected one of ['ME'], got 'YOU'"),
    ({"kind": "quake"}, "unknown kind 'quake'; known: add remove knock slip"),
    ({"kind": "knock", "block": "B", "force": 3},
     "unknown field 'force'; known: kind, block, speed"),
    (["knock"], 'expected a map with a "kind"'),
    ({"kind": "slip", "agent": {"k1": []}}, "agent: expected an agent's name, got {'k1': []}"),
]


@pytest.mark.parametrize("event, reason", BAD, ids=[r for _, r in BAD])
def test_a_bad_event_is_refused_with_the_reason(event, reason):
    w = world([["A", "B"]])
    before = w.snapshot_dict()
    out = w.inject(event)
    assert out["status"] == "failed" and out["event"] == event
    assert out["reason"].startswith("inject: ") and reason in out["reason"]
    assert w.snapshot_dict() == before


def test_a_block_held_by_a_gripper_cannot_be_knocked_or_removed():
    w = world([["A"]], holding={"ME": "C"})
    for kind in ("knock", "remove"):
        out = w.inject({"kind": kind, "block": "C"})
        assert "block C is held by ME's hand H1" in out["reason"]
