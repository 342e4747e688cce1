"""Percept intake: bad percepts are refused with a LangError naming the percept at every entry
point, also when the rest of the message equals last cycle's; the lazily built percept index
agrees with one built from Percept objects."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from agents.lang import Engine, LangError, Percept, load_program_text
from agents.lang.core.columns import plainly_valid, read_cols
from agents.lang.core.intake import PerceptIndex, frame_of
from agents.lang.core.terms import check_row

PROGRAM = load_program_text("""
(concepts
  ((heavy ?b) :percepts ((block ?b weight ?w)) :tests ((> ?w 2)))
  ((stack ?a ?b) :percepts ((block ?a xpos ?x) (block ?b xpos ?x)) :tests ((<> ?a ?b))))
(skills ((heavy ?b) :percepts ((block ?b)) :actions ((*lift ?b))))
(goals (heavy A))
""", "intake.tlp")

GOOD = [["block", "A", "xpos", 1, "weight", 3.5], ["block", "B", "xpos", 1, "weight", 1],
        ["lamp", "L", "on", "yes"]]
BAD = [
    (["block", "A", "xpos", 1, "weight", None], "value None is not a symbol or number"),
    (["block", "A", "xpos", True, "weight", 3.5], "value True is not a symbol or number"),
    (["block", "A", "xpos", 1, "weight"], "an even number of items"),
    (["block", "A", 7, 1, "weight", 3.5], "attribute name 7 is not a symbol"),
    ([3, "A"], "type must be a symbol"),
    (["block", "A", "xpos", [1], "weight", 3.5], "is not a symbol or number"),
    (["lamp", "L", "on", None], "value None"),  # a type no concept reads
    ("block", "expected [type, id, attr, value, ...]"),
    ([], "expected [type, id, attr, value, ...]"),
]


@pytest.mark.parametrize("bad,why", BAD)
def test_bad_percepts_are_refused_naming_the_percept(bad, why):
    engine = Engine(PROGRAM)
    engine.infer(GOOD)  # last cycle's columns are known: the checks take their short cut
    for call in (engine.infer, lambda ps: engine.cycle(engine.initial_state(), ps),
                 lambda ps: engine.decide(engine.initial_state(), ps, ())):
        percepts = [bad if (isinstance(bad, list) and bad[:2] == p[:2]) else p for p in GOOD]
        if percepts == GOOD:
            percepts = [*GOOD, bad]
        with pytest.raises(LangError, match="percept") as err:
            call(percepts)
        assert why in str(err.value)
        assert repr(bad) in str(err.value)
    assert engine.infer(GOOD) == Engine(PROGRAM).infer(GOOD)


def test_a_refused_message_changes_nothing():
    """The good part of a refused message is not taken in either."""
    engine = Engine(PROGRAM)
    engine.infer(GOOD)
    moved = [["block", "A", "xpos", 2, "weight", 1.0], GOOD[1], ["lamp", "L", "on", None]]
    with pytest.raises(LangError, match="None"):
        engine.infer(moved)
    assert engine.infer(GOOD[:2]) == Engine(PROGRAM).infer(GOOD[:2])
    assert engine.last_infer_stats.mode == "unchanged"


def test_a_bool_equal_to_last_cycles_int_is_still_refused():
    engine = Engine(PROGRAM)
    engine.infer([["block", "A", "xpos", 1, "weight", 1]])
    with pytest.raises(LangError, match="True"):
        engine.infer([["block", "A", "xpos", 1, "weight", True]])


def test_columns_are_read_only_from_regular_rows():
    rows = [["b", f"B{i}", "x", i, "y", 2.5] for i in range(600)]
    cols = read_cols(rows, None)
    assert cols.names == ("x", "y") and cols.vals["x"][599] == 599 and cols.ids[0] == "B0"
    assert read_cols([*rows, ["b", "B600", "y", 1, "x", 2]], None) is None  # names differ
    assert read_cols([*rows, ["b", "B0", "x", 1, "y", 2]], None) is None  # id given twice
    assert read_cols([*rows[:300], ["b", "Z", "x", 1], *rows[300:]], None) is None
    again = read_cols([list(r) for r in rows], cols)
    assert again.same_ids and again.types["x"] is cols.types["x"]


@pytest.mark.parametrize("lamps", [1, 100])  # a small index is built at once, a big one lazily
def test_lazy_percept_index_agrees_with_percept_objects(lamps):
    rows = [["block", "A", "xpos", 1, "weight", 3.5], ["block", "A", "color", "red"],
            *[["lamp", f"L{i}", "on", "yes"] for i in range(lamps)], ["block", "B", "xpos", 1]]
    lazy = frame_of([list(r) for r in rows]).index
    eager = PerceptIndex([Percept.from_list(r) for r in rows])
    assert lazy.by_id.get(("block", "A")) == eager.by_id.get(("block", "A"))
    assert lazy.by_id.get(("block", "Z"), ()) == () and lazy.by_type.get("car", ()) == ()
    assert lazy.by_id[("lamp", "L0")] == eager.by_id[("lamp", "L0")]
    assert dict(lazy.by_type) == dict(eager.by_type)
    assert dict(lazy.by_id) == dict(eager.by_id)
    assert lazy.attr_index("block", "xpos") == eager.attr_index("block", "xpos")


def test_percepts_made_from_rows_behave_as_constructed_ones():
    row = ["self", "ME", "speed", 20.0, "limit", 25]
    p, q = Percept.of_row(row), Percept("self", "ME", (("speed", 20.0), ("limit", 25)))
    row[3] = 99.0  # the caller's list changing later changes nothing
    assert p == q and hash(p) == hash(q) and p.get("speed") == 20.0
    assert p.to_list() == ["self", "ME", "speed", 20.0, "limit", 25] and str(p) == str(q)
    with pytest.raises(AttributeError):
        p.id = "YOU"


def test_the_executive_gets_last_cycles_percepts_where_rows_did_not_change():
    inference = Engine(PROGRAM).inference
    rows = [["block", f"B{i}", "xpos", i, "weight", 1.5] for i in range(100)]
    inference.run(rows)
    before = inference.frame.index.by_type["block"]
    rows = [list(r) for r in rows]
    rows[7][5] = 2.5
    rows[9][5] = 1  # 1.5 -> 1: int now
    inference.run(rows)
    after = inference.frame.index.by_type["block"]
    assert [i for i, (p, q) in enumerate(zip(before, after, strict=True)) if p is not q] == [7, 9]
    assert after[7].get("weight") == 2.5 and str(after[9]) == "(block B9 xpos 9 weight 1)"
    assert after == [Percept.from_list(r) for r in rows]


def test_decide_alone_reuses_percepts_only_of_rows_it_has_seen():
    """An executive fed lists, then Percept objects, then lists again gets each cycle's own
    percepts (never a Percept of another cycle)."""
    engine = Engine(PROGRAM)
    rows = [["block", f"B{i}", "xpos", i, "weight", 1.5] for i in range(100)]
    for ps in (rows, [Percept.from_list([*r[:5], 9.5]) for r in rows],
               [[*r[:5], 7.5] for r in rows]):
        index = engine._index(ps)
        assert index.by_type["block"][3] == Percept.from_list(ps[3])


_ITEM = st.one_of(st.text(max_size=3), st.integers(), st.floats(allow_nan=False), st.booleans(),
                  st.none(), st.just([1]))
_ROW = st.one_of(st.lists(_ITEM, max_size=7),
                 st.builds(lambda t, i, kv: [t, i, *(x for p in kv for x in p)],
                           st.sampled_from(["block", "lamp"]), _ITEM,
                           st.lists(st.tuples(_ITEM, _ITEM), max_size=3)))


@given(st.lists(_ROW, max_size=6))
def test_rows_plainly_valid_at_once_are_what_check_row_accepts(rows):
    """``plainly_valid`` over a whole message says yes exactly when every row passes
    ``check_row`` (the values here are of exact types: no subclass to fall back for)."""
    def accepted(row):
        try:
            check_row(row)
        except LangError:
            return False
        return True
    assert plainly_valid(rows) == all(map(accepted, rows))
