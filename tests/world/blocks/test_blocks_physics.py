"""Real stacking in pymunk: towers stand under gravity, unsupported blocks fall, and a fall is
reported (seed 000's Blocks World made physical)."""

from __future__ import annotations

from blocks_helpers import act, blocks_seen, seen, settle, world


def _fell(w) -> list[dict]:
    return [e for e in w.snapshot_dict()["events"] if e["kind"] == "fell"]


def _run_collecting_falls(w, cycles: int) -> list[dict]:
    falls = []
    for _ in range(cycles):
        w.step()
        falls += _fell(w)
    return falls


def test_a_tower_of_eight_stands_for_a_minute():
    w = world([list("ABCDEFGH")], table={"columns": 2})
    before = seen(w)
    assert [p[5] for p in before[2:]] == [2, 4, 6, 8, 10, 12, 14, 16]
    assert _run_collecting_falls(w, 120) == [] and seen(w) == before


def test_a_wide_block_centred_on_a_narrow_one_stands():
    w = world([["A", "B", "C"]], sizes={"A": [0.5, 2.0], "B": [3.0, 1.0], "C": [1.0, 1.0]})
    before = blocks_seen(w)
    assert _run_collecting_falls(w, 20) == [] and blocks_seen(w) == before


def test_a_block_whose_centre_overhangs_its_support_falls():
    """B and C stand 0.9 m further right each: together their centre of mass is 1.35 m right
    of A's centre, beyond A's edge (1 m): the top of the tower topples onto the table."""
    w = world([["A", "B", "C"]], offsets={"B": 0.9, "C": 0.9})
    falls = _run_collecting_falls(w, 12)
    assert sorted(f["block"] for f in falls) == ["B", "C"]
    assert all(f["agent"] == "" and f["on"] == ["T"] for f in falls)
    assert {b: y for b, (_, y, _) in blocks_seen(w).items()} == {"A": 2, "B": 2, "C": 2}


def test_an_overhang_within_the_edge_stands():
    w = world([["A", "B"]], offsets={"B": 0.75})
    assert _run_collecting_falls(w, 12) == [] and blocks_seen(w)["B"] == (0.75, 4, 2)


def test_a_block_added_off_centre_on_a_narrow_block_falls():
    w = world([["A"]], sizes={"A": [1.0, 2.0]})
    out = w.inject({"kind": "add", "block": "B", "on": "A", "offset": 1.0})
    assert out["status"] == "done"
    falls = _run_collecting_falls(w, 8)
    assert [(f["block"], f["on"]) for f in falls] == [("B", ["T"])]
    assert blocks_seen(w)["B"][1] == 2          # on the table now


def test_a_knocked_block_falls_off_its_tower():
    w = world([["A", "B", "C"]])
    assert w.inject({"kind": "knock", "block": "C", "speed": 4.0})["status"] == "done"
    falls = _run_collecting_falls(w, 10)
    assert [f["block"] for f in falls] == ["C"]
    assert blocks_seen(w)["C"][1:] == (2, 2) and blocks_seen(w)["B"] == (0, 4, 2)


def test_a_block_knocked_off_the_table_lies_on_the_floor_out_of_reach():
    w = world([[], [], [], [], [], ["A"]])
    w.inject({"kind": "knock", "block": "A", "speed": 8.0})
    falls = _run_collecting_falls(w, 12)
    assert [(f["block"], f["on"]) for f in falls] == [("A", ["floor"])]
    assert blocks_seen(w)["A"][1] == 0          # the floor is at y = 0
    assert "A is not on T: it is on floor" in act(w, "*pickup", "A", "T")["reason"]


def test_a_slipping_gripper_drops_its_block_and_it_counts():
    w = world([["A", "B", "C"]])
    act(w, "*unstack", "C", "B")
    assert w.inject({"kind": "slip", "agent": "ME"})["status"] == "done"
    settle(w, 4)
    assert seen(w)[1] == ["hand", "H1", "status", "empty"]
    assert blocks_seen(w)["C"] == (0, 6, 2)     # it fell back onto B, 1 m below the jaws
    assert w.snapshot_dict()["counters"]["ME"]["blocks_dropped"] == 1


def test_a_fall_of_a_tower_an_agent_just_loaded_is_blamed_on_it():
    """Cycle 0 of an unstable start: the agent stacks D on the top of a tower that cannot
    hold, and the blocks it loaded fall in that cycle's step: they count against it."""
    w = world([["A", "B", "C"]], offsets={"B": 0.9, "C": 0.9}, holding={"ME": "D"})
    assert w.apply_actions("ME", [["*stack", "D", "C"]])[0]["status"] == "done"
    falls = _run_collecting_falls(w, 12)
    assert {f["block"] for f in falls} >= {"C", "D"}
    assert all(f["agent"] == "ME" for f in falls)
    assert w.snapshot_dict()["counters"]["ME"]["blocks_dropped"] == len(falls)
