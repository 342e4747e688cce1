"""Work carried across cycles: an Engine that keeps its facts from cycle to cycle gives, cycle by
cycle, exactly what a fresh Engine gives on the same percepts, and strata that read nothing that
changed are not evaluated at all (tests/lang/test_incremental.py has random programs)."""

from __future__ import annotations

import marshal

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Engine, load_program_text
from agents.lang.core.store import PerceptIndex

from .conftest import ROOT

# Several percept types, recursion, negation and a concept that reads no percepts, so that a
# change to one type leaves other strata untouched.
GRAPH = """
(concepts
  ((link ?a ?b) :percepts ((edge ?e from ?a to ?b)))
  ((reach ?a ?b) :relations ((link ?a ?b)))
  ((reach ?a ?c) :relations ((link ?a ?b) (reach ?b ?c)))
  ((big ?x) :percepts ((node ?x size ?s)) :tests ((> ?s 2)))
  ((size ?x ?s) :percepts ((node ?x size ?s)))
  ((cut-off ?x) :percepts ((node ?x)) :relations ((not (reach ?x ?x)) (not (big ?x))))
  ((big-reach ?a ?b) :relations ((reach ?a ?b) (big ?b)))
  ((lit ?f) :percepts ((lamp ?f state on)))
  ((dark) :percepts ((lamp ?f state off)) :relations ((not (lit ?f)))))
"""

NODES = ["A", "B", "C", "D"]
SIZES = [0, 1, 2, 3, 3.0, 4, -0.0, 0.0]  # equal values of different types on purpose
PERCEPT = st.one_of(
    st.builds(lambda e, a, b: ["edge", e, "from", a, "to", b],
              st.sampled_from(["E1", "E2", "E3", "E4"]), st.sampled_from(NODES),
              st.sampled_from(NODES)),
    st.builds(lambda x, s: ["node", x, "size", s], st.sampled_from(NODES), st.sampled_from(SIZES)),
    st.builds(lambda f, s: ["lamp", f, "state", s], st.sampled_from(["L1", "L2"]),
              st.sampled_from(["on", "off"])),
)
CHANGE = st.one_of(
    st.just(("same", None)), st.just(("shuffle", None)), st.tuples(st.just("add"), PERCEPT),
    st.tuples(st.just("drop"), st.integers(0, 30)), st.tuples(st.just("swap"), PERCEPT))


def apply(change: tuple, percepts: list, rnd) -> list:
    """One small change between cycles (``rnd`` also reorders the percepts sometimes)."""
    kind, arg = change
    out = list(percepts)
    if kind == "add":
        out.append(arg)
    elif kind == "drop" and out:
        out.pop(arg % len(out))
    elif kind == "swap" and out:
        out[rnd.randrange(len(out))] = arg
    if kind == "shuffle" or rnd.random() < 0.3:
        rnd.shuffle(out)
    return out


def shown(beliefs) -> list[str]:
    """Beliefs as sorted text: tells 3 from 3.0 and 0.0 from -0.0, which == does not."""
    return sorted(str(b) for b in beliefs)


def mixed(percepts: list) -> bool:
    """True when one cycle holds equal values of different types (3 and 3.0): a belief set
    keeps whichever came first, so its text depends on percept order even without reuse."""
    values = [v for p in percepts for v in p]
    return len(set(values)) != len({marshal.dumps(v, 2) for v in values})


GRAPH_PROGRAM = load_program_text(GRAPH, "graph.tlp")


@settings(max_examples=80, deadline=None)
@given(st.lists(PERCEPT, max_size=8), st.lists(CHANGE, min_size=1, max_size=8),
       st.randoms(use_true_random=False))
def test_cycles_with_reuse_equal_fresh_engine(first, changes, rnd):
    engine = Engine(GRAPH_PROGRAM)
    percepts = first
    for change in [("same", None), *changes]:
        got = engine.infer(percepts)
        want = Engine(GRAPH_PROGRAM).infer(percepts)
        assert got == want
        assert got.store.beliefs() == want.store.beliefs()
        if not mixed(percepts):
            assert shown(got) == shown(want)
        percepts = apply(change, percepts, rnd)


def test_unchanged_and_reordered_percepts_evaluate_nothing():
    engine = Engine(GRAPH_PROGRAM)
    ps = [["edge", "E1", "from", "A", "to", "B"], ["node", "A", "size", 3],
          ["lamp", "L1", "state", "off"]]
    first = engine.infer(ps)
    assert engine.last_infer_stats.evaluated == engine.last_infer_stats.strata
    again = engine.infer(ps[::-1])
    assert engine.last_infer_stats.evaluated == 0
    assert engine.last_infer_stats.reused == engine.last_infer_stats.strata
    assert engine.last_infer_stats.mode == "unchanged"
    # the BeliefSet itself is handed out again, and its store is the live one
    assert again is first and again.store is engine.inference.idb
    assert engine.infer([list(p) for p in ps]) is again


def test_a_change_reevaluates_only_what_depends_on_it():
    engine = Engine(GRAPH_PROGRAM)
    ps = [["edge", "E1", "from", "A", "to", "B"], ["node", "B", "size", 3],
          ["lamp", "L1", "state", "off"]]
    engine.infer(ps)
    engine.infer([*ps[:2], ["lamp", "L1", "state", "on"]])
    # only lit and dark read lamps; link, reach, big, size, cut-off, big-reach are untouched
    assert engine.last_infer_stats.evaluated == 2
    assert engine.last_infer_stats.changed == ("dark", "lit")
    # 3 -> 3.0 is a change although 3 == 3.0: the belief (size B 3.0) prints differently;
    # the lamp goes back off too. link and reach read no node or lamp: not evaluated
    got = engine.infer([ps[0], ["node", "B", "size", 3.0], ps[2]])
    assert "(size B 3.0)" in shown(got)
    assert engine.last_infer_stats.evaluated == engine.last_infer_stats.strata - 2


def test_cycle_decisions_equal_fresh_engine(blocks):
    """Blocks World through whole cycles (infer + decide), the goal stack carried along."""
    from .test_blocks import percepts as block_percepts

    engine = Engine(blocks.program)
    fresh_state = state = engine.add_goal(engine.initial_state(), "(on A C)", priority=0)
    worlds = [({"A": "T", "B": "A", "C": "T"}, None), ({"A": "T", "B": "A", "C": "T"}, None),
              ({"A": "T", "C": "T"}, "B"), ({"A": "T", "C": "T"}, "B"),
              ({"A": "T", "B": "T", "C": "T"}, None)]
    for support, holding in worlds:
        ps = block_percepts(support, holding)
        got = engine.cycle(state, ps[::-1])
        want = Engine(blocks.program).cycle(fresh_state, ps)
        assert got.beliefs == want.beliefs
        assert got.decision.to_dict() == want.decision.to_dict()
        assert got.state == want.state
        state, fresh_state = got.state, want.state


def test_decide_after_infer_on_the_same_percepts_equals_a_fresh_reading(blocks):
    """decide after infer, given the very list infer was given, an equal one, or other
    percepts: every decision is the same as ``cycle``'s and a fresh engine's."""
    from .test_blocks import percepts as block_percepts

    engine, fresh = Engine(blocks.program), Engine(blocks.program)
    state = fresh_state = engine.add_goal(engine.initial_state(), "(on A C)", priority=0)
    worlds = [({"A": "T", "B": "A", "C": "T"}, None), ({"A": "T", "C": "T"}, "B"),
              ({"A": "T", "C": "T"}, "B"), ({"A": "T", "B": "T", "C": "T"}, None)]
    for k, (support, holding) in enumerate(worlds):
        ps = block_percepts(support, holding)
        beliefs = engine.infer(ps)
        given = ps if k % 2 == 0 else [list(p) for p in ps]  # the same list, or an equal one
        decision, state = engine.decide(state, given, beliefs)
        want = fresh.cycle(fresh_state, ps)
        assert decision.to_dict() == want.decision.to_dict()
        assert state == want.state
        fresh_state = want.state
    other = block_percepts({"A": "T", "B": "T", "C": "T"}, None)
    engine.infer(block_percepts({"A": "T", "C": "T"}, "B"))
    decision, _ = engine.decide(state, other, Engine(blocks.program).infer(other))
    want = Engine(blocks.program).cycle(state, other)
    assert decision.to_dict() == want.decision.to_dict()


def test_blocks_program_evaluates_nothing_for_an_unchanged_world():
    from agents.lang import load_program

    engine = Engine(load_program(ROOT / "programs" / "blocks.tlp"))
    ps = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"],
          ["block", "A", "xpos", 0, "ypos", 2, "height", 2]]
    engine.infer(PerceptIndex([]))
    engine.infer(ps)
    engine.infer(list(ps))
    assert engine.last_infer_stats.evaluated == 0


def test_decide_after_infer_reads_a_list_changed_in_place_afresh(blocks):
    """Code review 2026-12-04 section 3.2 (issue 36): ``infer(p)``, then one element of the
    same list ``p`` replaced in place (block A becomes block X), then ``decide(state, p, ...)``
    must decide on what ``p`` holds now, as a fresh engine does, not on infer's reading of it
    (that gave an impasse, 'no executable skill path')."""
    from .test_blocks import percepts as block_percepts

    engine = Engine(blocks.program)
    state = engine.add_goal(engine.initial_state(), "(clear B)", priority=0)
    p = block_percepts({"A": "B", "B": "T", "C": "T"})
    engine.infer(p)
    k = next(i for i, row in enumerate(p) if row[:2] == ["block", "A"])
    p[k] = ["block", "X"] + p[k][2:]
    decision, _ = engine.decide(state, p, Engine(blocks.program).infer(p))
    want = Engine(blocks.program).cycle(state, list(p))
    assert decision.to_dict() == want.decision.to_dict()
    assert want.decision.actions, "the fresh engine acts: the test must compare an action"
