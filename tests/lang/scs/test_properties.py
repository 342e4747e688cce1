"""Properties over random inputs (hypothesis).

Seed 002, Appendix B/C: 'do first ... behaves almost the same as a T-R program ... To
persistently try a step with satisfied conditions even if it fails (as in T-R programs), the
do* first construct can be used.' So do*-first over pairs (Ki -> ai) acts exactly as the
equivalent teleoreactive sequence written as an ordinary prioritised skill list (skill i
requires Ki and no earlier Kj), on any sequence of percepts and any action outcomes."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, EngineState, load_program_text
from agents.lang.scs.state import Choice, Frame, ScsState, Thread, ThreadStatus

K = ["k1", "k2", "k3", "k4"]
HEAD = """(concepts ((flag ?f) :percepts ((flag ?f))) ((never ?x) :percepts ((never ?x))))
(goals (never ME))
"""


def scs_program(n: int) -> Engine:
    pairs = " ".join(f"(((flag {k})) (*a{i}))" for i, k in enumerate(K[:n]))
    body = f"(do*-first {pairs})"
    return Engine(load_program_text(HEAD + f"(skills ((never ?x) :percepts ((self ?x)) "
                                           f":body {body}))", "scs.tlp"), solver=None)


def tr_program(n: int) -> Engine:
    skills = []
    for i, k in enumerate(K[:n]):
        earlier = " ".join(f"(not (flag {j}))" for j in K[:i])
        skills.append(f"((never ?x) :percepts ((self ?x)) :requires ((flag {k}) {earlier}) "
                      f":actions ((*a{i})))")
    return Engine(load_program_text(HEAD + "(skills " + "\n".join(skills) + ")", "tr.tlp"),
                  solver=None)   # Appendix B compares the circuits alone, with no problem solver


def run(engine: Engine, cycles: list[tuple[frozenset, bool]], seed: int) -> list:
    state, outcomes, out = engine.initial_state(seed=seed), [], []
    for flags, fails in cycles:
        percepts = [["self", "ME"], *(["flag", f] for f in sorted(flags))]
        result = engine.cycle(state, percepts, outcomes)
        state = result.state
        actions = [a.to_list() for a in result.decision.actions]
        outcomes = [{"action": a, "status": "failed" if fails else "done",
                     "reason": "forced" if fails else ""} for a in actions]
        out.append(actions)
    return out


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 4),
       st.lists(st.tuples(st.frozensets(st.sampled_from(K)), st.booleans()), min_size=1,
                max_size=25),
       st.integers(0, 3))
def test_do_star_first_gives_the_action_trace_of_the_teleoreactive_sequence(n, cycles, seed):
    assert run(scs_program(n), cycles, seed) == run(tr_program(n), cycles, seed)


consts = st.one_of(st.integers(-5, 5), st.sampled_from(["ME", "T", "NIL", "S12"]),
                   st.floats(-10, 10, allow_nan=False).map(lambda x: round(x, 3)))
names = st.sampled_from(["x", "p", "self", "d"])


def frames(depth: int = 3):
    leaf = st.builds(Frame, st.tuples(st.integers(0, 4)),
                     st.lists(st.tuples(names, consts), max_size=2).map(tuple),
                     st.integers(-1, 3), st.lists(st.integers(0, 3), max_size=2).map(tuple),
                     st.lists(st.integers(0, 3), max_size=2).map(tuple),
                     st.lists(st.tuples(names, consts), max_size=1).map(tuple),
                     st.integers(0, 4), st.integers(0, 4), st.integers(-1, 9),
                     st.integers(-1, 9), st.none(),
                     st.lists(st.tuples(st.sampled_from(["*a", "*gas"]), consts),
                              max_size=2).map(tuple),
                     st.integers(-1, 9), st.sampled_from(["", "done", "failed"]),
                     st.sampled_from(["", "forced"]))
    if depth == 0:
        return leaf
    return st.one_of(leaf, st.builds(lambda f, c: Frame(f.at, f.bind, cur=f.cur, child=c),
                                     leaf, frames(depth - 1)))


states = st.builds(
    ScsState,
    st.lists(st.builds(lambda k, f, s: Thread(f"g{k}|(never ME)|0", f"g{k}", "(never ME)", 0,
                                              "never#1", f, s, "note", k, k + 1),
                       st.integers(0, 5), st.one_of(st.none(), frames()),
                       st.sampled_from(list(ThreadStatus))),
             max_size=3, unique_by=lambda t: t.key).map(
        lambda ts: tuple(sorted(ts, key=lambda t: t.key))),
    st.lists(st.builds(Choice, st.sampled_from(["a@0", "b@1", "c@0.2"]), st.just("(*a) x:1:1"),
                       st.floats(0, 1).map(lambda x: round(x, 6)), st.integers(0, 9),
                       st.integers(0, 9), st.integers(0, 9)),
             max_size=3, unique_by=lambda c: c.key).map(
        lambda cs: tuple(sorted(cs, key=lambda c: c.key))),
    st.lists(st.tuples(st.sampled_from(["seen", "mark"]), consts), max_size=3).map(
        lambda fs: tuple(sorted(set(fs), key=lambda f: (f[0], str(type(f[1])), str(f[1]))))),
    st.dictionaries(st.sampled_from(["actions done", "bodies failed"]), st.integers(0, 50)).map(
        lambda d: tuple(sorted(d.items()))))


@settings(max_examples=150, deadline=None)
@given(states)
def test_scs_state_round_trips_through_json(scs):
    state = EngineState(scs=scs)
    back = EngineState.from_dict(json.loads(json.dumps(state.to_dict())))
    assert back.scs.threads == scs.threads and back.scs.choices == scs.choices
    assert back.scs.tally == scs.tally and set(back.scs.model) == set(scs.model)
