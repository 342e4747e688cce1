"""The matcher remembers which condition it takes first for a set of conditions and the
variables bound when it starts (agents/lang/core/matcher.py, ``solve``): the choice depends on
nothing else, so an engine whose matcher has remembered orders from earlier cycles (and from
other engines of the same program) decides exactly as one starting with none. Random programs
with skills over their concepts and random percept sequences (tests/lang/test_intake_paths.py's),
compared every cycle."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, load_program_text
from agents.lang.core import matcher, terms
from agents.lang.core.store import FactStore, PerceptIndex
from agents.lang.core.terms import Expr, Literal, PerceptPattern, Var

from .test_incremental import CHANGE, ROW, programs
from .test_intake_paths import SKILLS, decided, mixed, step


@settings(max_examples=100, deadline=None)
@given(programs(), st.lists(ROW, min_size=2, max_size=10),
       st.lists(CHANGE, min_size=1, max_size=10), st.randoms(use_true_random=False))
def test_remembered_orders_give_the_decisions_of_an_engine_without_them(text, rows, changes,
                                                                         rnd):
    program = load_program_text(text + SKILLS, "random.tlp")
    warm = Engine(program)
    state = warm.initial_state()
    for change in [("same",), *changes]:
        got = warm.cycle(state, [list(r) for r in rows])
        matcher._PICKS.clear()
        fresh = Engine(program).cycle(state, [list(r) for r in rows])
        if not mixed(rows):
            assert got.beliefs == fresh.beliefs, (text, rows)
            assert decided(got.decision) == decided(fresh.decision), (text, rows)
            assert got.state == fresh.state
        state = fresh.state
        rows = step(change, rows, rnd)


X, Y, V = Var("x"), Var("y"), Var("v")
CONDS = [terms.Test(Expr(">", (V, 1))), Literal("near", (X, Y)),
         PerceptPattern("obj", X, (("v", V),)), Literal("far", (X, Y), negated=True)]


@settings(max_examples=100, deadline=None)
@given(st.lists(st.tuples(st.sampled_from("ABC"), st.integers(0, 3)), max_size=5),
       st.sets(st.tuples(st.sampled_from("ABC"), st.sampled_from("ABC")), max_size=5),
       st.sets(st.tuples(st.sampled_from("ABC"), st.sampled_from("ABC")), max_size=3),
       st.lists(st.sampled_from([{}, {X: "A"}, {Y: "B"}, {X: "C", Y: "A"}, {V: 2}]),
                min_size=1, max_size=6))
def test_solutions_do_not_depend_on_the_orders_remembered(objs, near, far, starts):
    """The same conditions from bindings of the same variables but other values, in any
    sequence: each gives, in the same order, what it gives with nothing remembered."""
    pidx = PerceptIndex.of_groups({"obj": [["obj", o, "v", v] for o, v in dict(objs).items()]}
                                  if objs else {})
    store = FactStore({"near": set(near), "far": set(far)})
    warm = [list(matcher.solve(CONDS, dict(b), pidx, store)) for b in starts]
    for b, got in zip(starts, warm, strict=True):
        matcher._PICKS.clear()
        assert got == list(matcher.solve(CONDS, dict(b), pidx, store))
