"""The engine's ways of taking percepts in agree, beliefs and decisions alike: ``infer`` then
``decide`` on plain lists (each reads the rows itself), ``cycle`` (one reading for both), the
same rows as ``SharedRows`` (an unchanged row is the same object, read without reading it
again), and a fresh Engine every cycle. Random programs (tests/lang/test_incremental.py's
generator) with skills over their concepts, random percept sequences, cycle by cycle from the
same state (issue 36: evaluation that fits the frame gives exactly the same beliefs and
decisions)."""

from __future__ import annotations

import marshal

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, LangError, SharedRows, load_program_text

from .test_incremental import CHANGE, ROW, programs

# Skills over the generator's first two concepts (c0 unary, c1 binary); actions carry percept
# values, so a belief or binding of 3 where a fresh engine has 3.0 shows in the decision.
SKILLS = """
(skills
  ((c0 ?x) :percepts ((obj ?x v ?v)) :requires ((c1 ?x ?y)) :actions ((*touch ?x ?y ?v)))
  ((c0 ?x) :percepts ((obj ?x w ?w)) :actions ((*poke ?x ?w)))
  ((c1 ?x ?y) :percepts ((obj ?x k ?k)) :subgoals ((c0 ?x)))
  ((c1 ?x ?y) :percepts ((link ?l from ?x to ?y)) :actions ((*follow ?l))))
(goals
  (c0 O1)
  (c1 O2 O3)
  (c0 O4))
"""


def step(change: tuple, rows: list, rnd) -> list:
    """One change between cycles that keeps every untouched row the same object (as the bus
    decodes a row it has seen before) and makes a new list of a changed one."""
    out = list(rows)
    kind = change[0]
    if kind == "add":
        out.append(list(change[1]))
    elif kind == "drop" and out:
        out.pop(change[1] % len(out))
    elif kind == "swap" and out:
        out[change[1] % len(out)] = list(change[2])
    elif kind == "set" and out:
        k = change[1] % len(out)
        row = list(out[k])
        if len(row) > 2:
            row[3 + 2 * rnd.randrange((len(row) - 2) // 2)] = change[2]
        out[k] = row
    if kind == "shuffle":
        rnd.shuffle(out)
    return out


def mixed(rows: list) -> bool:
    """True when one cycle holds equal values of different types or zero sign (3 and 3.0):
    which of them a belief takes then depends on evaluation order, even from scratch."""
    values = [v for r in rows for v in r]
    return len(set(values)) != len({marshal.dumps(v, 2) for v in values})


def decided(decision) -> dict:
    """The decision as data, every action value tagged with its exact type."""
    d = decision.to_dict()
    d["typed"] = [[(type(v).__name__, repr(v)) for v in a.to_list()]
                  for a in decision.actions]
    return d


@settings(max_examples=120, deadline=None)
@given(programs(), st.lists(ROW, min_size=2, max_size=10),
       st.lists(CHANGE, min_size=1, max_size=10), st.randoms(use_true_random=False))
def test_every_intake_gives_a_fresh_engines_beliefs_and_decisions(text, rows, changes, rnd):
    program = load_program_text(text + SKILLS, "random.tlp")
    plain, whole, shared = Engine(program), Engine(program), Engine(program)
    state = plain.initial_state()
    for change in [("same",), *changes]:
        fresh = Engine(program).cycle(state, [list(r) for r in rows])
        got = []
        beliefs = plain.infer([list(r) for r in rows])
        decision, after = plain.decide(state, [list(r) for r in rows], beliefs)
        got.append((beliefs, decision, after))
        r = whole.cycle(state, [list(r) for r in rows])
        got.append((r.beliefs, r.decision, r.state))
        beliefs = shared.infer(SharedRows(rows))
        decision, after = shared.decide(state, SharedRows(rows), beliefs)
        got.append((beliefs, decision, after))
        if not mixed(rows):
            for beliefs, decision, after in got:
                assert beliefs == fresh.beliefs, (text, rows)
                assert sorted(map(str, beliefs)) == sorted(map(str, fresh.beliefs))
                assert decided(decision) == decided(fresh.decision), (text, rows)
                assert after == fresh.state
        state = fresh.state
        rows = step(change, rows, rnd)


def test_a_bad_row_is_refused_by_every_intake_and_the_next_cycle_is_read_afresh():
    """A refused message changes nothing: the rows after it give what a fresh engine gives."""
    program = load_program_text("(concepts ((hot ?x) :percepts ((obj ?x v ?v)) :tests "
                                "((> ?v 2)))) (skills ((hot ?x) :percepts ((obj ?x)) "
                                ":actions ((*heat ?x)))) (goals (hot O1))", "bad.tlp")
    good = [["obj", "O1", "v", 1], ["obj", "O2", "v", 5]]
    bad = [good[0], ["obj", "O2", "v", [5]]]
    for wrap in (list, SharedRows):
        engine = Engine(program)
        state = engine.initial_state()
        engine.decide(state, wrap(good), engine.infer(wrap(good)))
        with pytest.raises(LangError, match="O2"):
            engine.infer(wrap(bad))
        beliefs = engine.infer(wrap(good))
        with pytest.raises(LangError, match="O2"):
            engine.decide(state, wrap(bad), beliefs)
        after = [good[0], ["obj", "O2", "v", 1.5]]
        beliefs = engine.infer(wrap(after))
        decision, _ = engine.decide(state, wrap(after), beliefs)
        want = Engine(program).cycle(state, after)
        assert beliefs == want.beliefs
        assert decided(decision) == decided(want.decision)
        assert [str(a) for a in decision.actions] == ["(*heat O1)"]
