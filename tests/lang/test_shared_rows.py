"""Percepts as the bus delivers them, their unchanged rows shared
(agents/lang/inference/shared_rows.py):
inference and the executive reach the same beliefs and decisions as on plain lists, reading
only the rows that are new, and a bad new row is still refused by name."""

from __future__ import annotations

import marshal
import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, LangError, SharedRows, load_program, load_program_text

from .conftest import ROOT
from .test_incremental import CHANGE, ROW, apply, assert_same_beliefs, programs


class Bus:
    """What bus/codec.py does for one key: a row equal, byte for byte, to one of the last
    message's is that very object (marshal tells 3 from 3.0 and 0.0 from -0.0, as msgpack
    does)."""

    def __init__(self) -> None:
        self.last: dict[bytes, list] = {}

    def deliver(self, rows: list) -> SharedRows:
        now: dict[bytes, list] = {}
        out = []
        for r in rows:
            key = marshal.dumps(r, 2)
            got = now.setdefault(key, self.last.get(key, r))
            out.append(got)
        self.last = now
        return SharedRows(out)


@settings(max_examples=300, deadline=None)
@given(programs(), st.lists(ROW, min_size=2, max_size=10),
       st.lists(CHANGE, min_size=1, max_size=12), st.randoms(use_true_random=False))
def test_shared_rows_give_the_beliefs_of_plain_lists(text, rows, changes, rnd):
    program = load_program_text(text, "random.tlp")
    engine, plain, bus = Engine(program), Engine(program), Bus()
    for change in [("same",), *changes]:
        got = engine.infer(bus.deliver(rows))
        want = plain.infer([list(r) for r in rows])
        assert_same_beliefs(got, want, engine, text, rows)
        rows = apply(change, rows, rnd)


def towers(n: int, rnd: random.Random) -> list[list]:
    """Table, hand and ``n`` blocks in towers of up to three, each with a distance [m]."""
    out = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"]]
    for i in range(n):
        out.append(["block", f"B{i}", "xpos", 3 * (i // 3), "ypos", 2 + 2 * (i % 3),
                    "height", 2, "color", rnd.choice(["red", "blue"]),
                    "distance", round(rnd.uniform(0, 20), 2)])
    return out


BLOCKS = load_program(ROOT / "tests" / "lang" / "fixtures" / "blocks_handwritten.tlp",
                      ROOT / "bench" / "speed" / "towers.tlp")


def test_one_distance_changing_reads_one_row_and_decides_as_plain_lists():
    rnd = random.Random(3)
    rows = towers(30, rnd)
    shared, plain, bus = Engine(BLOCKS, solver=None), Engine(BLOCKS, solver=None), Bus()
    states = [s.add_goal(s.initial_state(), "(clear B0)", priority=0) for s in (shared, plain)]
    for cycle in range(12):
        got = shared.cycle(states[0], bus.deliver(rows))
        want = plain.cycle(states[1], [list(r) for r in rows])
        assert got.beliefs == want.beliefs
        assert got.decision.to_dict() == want.decision.to_dict()
        states = [got.state, want.state]
        rows = [list(r) for r in rows]
        if cycle % 3 == 2:
            continue  # nothing changes: the cycle reads no row
        rows[2 + cycle][11] = round(rows[2 + cycle][11] + 0.5, 2)
    shared.infer(bus.deliver([list(r) for r in rows]))  # the same values in new lists
    assert shared.last_infer_stats.mode == "unchanged"


def test_a_bad_value_in_a_new_row_is_refused_by_name():
    bus, engine = Bus(), Engine(BLOCKS, solver=None)
    rows = towers(6, random.Random(1))
    engine.infer(bus.deliver(rows))
    rows = [list(r) for r in rows]
    rows[4][11] = None
    with pytest.raises(LangError, match="B2"):
        engine.infer(bus.deliver(rows))
    rows[4][11] = 1.5  # the next good message is read as usual
    assert engine.infer(bus.deliver(rows)) == Engine(BLOCKS, solver=None).infer(rows)


def test_rows_reordered_or_of_another_type_are_read_afresh():
    bus, engine = Bus(), Engine(BLOCKS, solver=None)
    first = towers(9, random.Random(2))
    engine.infer(bus.deliver(first))
    for rows in (first[::-1], first[:3] + [["hand", "H1", "status", "full"]] + first[4:],
                 first[:-1]):
        assert engine.infer(bus.deliver(rows)) == Engine(BLOCKS, solver=None).infer(rows)


def test_the_executive_on_shared_rows_decides_as_on_plain_lists():
    """As the executive process runs it: beliefs from elsewhere, percepts as the bus delivers
    them; rows kept from last cycle keep their Percept objects."""
    rnd = random.Random(5)
    rows = towers(24, rnd)
    shared, plain, bus = Engine(BLOCKS, solver=None), Engine(BLOCKS, solver=None), Bus()
    states = [e.add_goal(e.initial_state(), "(clear B3)", priority=0) for e in (shared, plain)]
    for cycle in range(15):
        beliefs = plain.infer([list(r) for r in rows])
        got, s0 = shared.decide(states[0], bus.deliver(rows), beliefs)
        want, s1 = plain.decide(states[1], [list(r) for r in rows], beliefs)
        assert got.to_dict() == want.to_dict()
        states = [s0, s1]
        rows = [list(r) for r in rows]
        if cycle % 4 == 1:
            rows[2 + rnd.randrange(24)][3] = 99  # a block moves away
        elif cycle % 4 == 2:
            rows[2 + rnd.randrange(24)][11] = 1.25
    index = shared._index(bus.deliver(rows))
    again = shared._index(bus.deliver([list(r) for r in rows]))
    assert again.by_type["block"][5] is index.by_type["block"][5]


def test_the_executive_refuses_a_bad_new_row_and_reads_the_next_message_afresh():
    bus, engine = Bus(), Engine(BLOCKS, solver=None)
    state = engine.initial_state()
    rows = towers(6, random.Random(4))
    beliefs = engine.infer([list(r) for r in rows])
    engine.decide(state, bus.deliver(rows), beliefs)
    bad = [list(r) for r in rows]
    bad[3][11] = None
    with pytest.raises(LangError, match="B1"):
        engine.decide(state, bus.deliver(bad), beliefs)
    with pytest.raises(LangError, match="B1"):  # the same bad row again is refused again
        engine.decide(state, bus.deliver([list(r) for r in bad]), beliefs)
    decision, _ = engine.decide(state, bus.deliver(rows), beliefs)
    assert decision.to_dict() == Engine(BLOCKS, solver=None).decide(state, rows, beliefs)[0] \
        .to_dict()
