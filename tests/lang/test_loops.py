"""The loop watch (agents/lang/execution/loops.py): a return to a situation already seen while
pursuing
a goal is found at once within the window, and by the Brent checkpoint for a circle longer than
the window (within twice its length); staying put, steps the agent did not cause, and
situations where the goal was not pursued do not count; digests do not depend on Python's
string hashing."""

from __future__ import annotations

from hashlib import blake2b

from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang.core.store import FactStore, PerceptIndex
from agents.lang.execution.loops import WINDOW, LoopState, Watch, situation, world

from .test_determinism import under_hash_seeds


def _walk(digests: list[str], caused: bool = True, pursued: bool = True) -> int | None:
    """Feed one situation per cycle to a goal's watch, the agent acting each time (its
    expected effect seen next cycle when ``caused``); the first cycle a return is found."""
    w = Watch("g1", 0)
    for cycle, d in enumerate(digests):
        if w.returned(d) is not None:
            return cycle
        w = w.seen(d, cycle, "g1", pursued, (("moved", cycle),), f"world{d}")
        w = w.observed(FactStore({"moved": {(cycle,)} if caused else set()}), f"world{d}")
    return None


def test_a_return_is_found_the_cycle_it_happens():
    assert _walk(["a", "b", "c", "b"]) == 3
    assert _walk(["a", "b", "a", "b"]) == 2


def test_staying_put_and_situations_never_left_are_not_returns():
    assert _walk(["a", "a", "a", "b", "c"]) is None


def test_steps_the_agent_did_not_cause_or_goals_not_pursued_do_not_count():
    assert _walk(["a", "b", "a", "b"], caused=False) is None
    assert _walk(["a", "b", "a", "b"], pursued=False) is None


@settings(max_examples=30, deadline=None)
@given(st.integers(2, 3 * WINDOW), st.integers(0, 10))
def test_a_circle_of_any_length_is_found_within_twice_its_length(period, lead):
    """``lead`` situations first (the approach), then a circle of ``period`` situations for
    ever: found before the circle has come round three times."""
    path = [f"lead{k}" for k in range(lead)] + [f"s{k % period}" for k in range(4 * period + 64)]
    found = _walk(path)
    assert found is not None and found <= lead + 3 * period + 2 * WINDOW


def test_a_watch_round_trips_as_plain_data():
    w = Watch("g1", 3)
    for cycle, d in enumerate("abc"):
        w = w.seen(d, cycle, "g1", True, (("on", "A", "B"),), "w" + d, cycle == 2)
    state = LoopState((w,))
    assert LoopState.from_dict(state.to_dict()) == state


SCRIPT = """
from agents.lang import Engine, load_program, as_percepts
from agents.lang.execution.loops import situation
from agents.lang.core.store import PerceptIndex, store_of
engine = Engine(load_program("programs/blocks.tlp"))
rows = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"],
        ["block", "A", "xpos", 0, "ypos", 2, "height", 2], ["block", "B", "xpos", 0,
        "ypos", 4, "height", 2]]
index = PerceptIndex(as_percepts(rows))
print(situation(index, store_of(engine.infer(index)), "intent"))
"""


def test_the_digest_is_the_same_in_every_process():
    outputs = under_hash_seeds(SCRIPT)
    assert outputs[0] == outputs[1] == outputs[2] and len(outputs[0].strip()) == 32
    assert situation.__doc__ and "no Python hash" in situation.__doc__


_ATOM = st.one_of(st.sampled_from(["A", "B", "ME", "a'b"]), st.integers(-3, 3),
                  st.sampled_from([0.0, -0.0, 1.0, 2.5]))


@settings(max_examples=150, deadline=None)
@given(rows=st.lists(st.tuples(st.sampled_from(["self", "street", "s"]), _ATOM, _ATOM),
                     max_size=6),
       facts=st.dictionaries(st.sampled_from(["on", "near", "clear", "o"]),
                             st.sets(st.tuples(_ATOM, _ATOM), max_size=4), max_size=4))
def test_the_world_digest_hashes_one_line_per_row_and_belief(rows, facts):
    """The world digest is the blake2b of each percept row's repr and each belief (its
    predicate then its tuple's repr) as sorted "\\n"-terminated lines, the parts split by "|"
    (the digests of earlier states compare equal to today's only if the bytes are these)."""
    index = PerceptIndex.of_groups({t: [[t, i, "v", v] for tt, i, v in rows if tt == t]
                                    for t in {r[0] for r in rows}})
    lines = [r + "\n" for r in sorted(repr((t, i, "v", v)) for t, i, v in rows)]
    lines += ["|"] + [f"{p}{x}\n" for p in sorted(facts) for x in sorted(map(repr, facts[p]))]
    want = blake2b("".join(lines).encode(), digest_size=16).hexdigest()
    assert world(index, FactStore({p: set(ts) for p, ts in facts.items()})) == want
