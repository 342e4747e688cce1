"""The engine's small case, where a cycle's work is mostly fixed costs: a variable is one object
per name (equal and hashed by identity); the effect model binds an action list only to the
primitive skills whose actions have its shape, giving what trying every skill gives; a fact
store keeps each relation's text for the loop watch's digest until the relation changes, and
the digest of a store changed step by step is that of a fresh store holding the same facts; a
remembered step's written-out text is the one its dataclass would generate."""

from __future__ import annotations

import copy
import dataclasses
import gc
import pickle
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from agents.lang import Literal, Var, load_program, load_program_text
from agents.lang.core.store import FactStore, PerceptIndex
from agents.lang.core.terms import Action, Expr
from agents.lang.execution.effects import Effects
from agents.lang.execution.loops import world
from agents.lang.execution.state import StoredStep

from .solving.test_stated_effects import program as blocks_with_effects

ROOT = Path(__file__).resolve().parents[2]


def test_a_variable_is_one_object_per_name():
    x = Var("x")
    assert Var("x") is x and Var("x") == x and hash(Var("x")) == hash(x)
    assert Var("y") is not x and Var("y") != x and x != "x" and x != "?x"
    assert pickle.loads(pickle.dumps(x)) is x
    assert copy.deepcopy(x) is x and copy.copy(x) is x
    assert repr(x) == "Var(name='x')" and str(x) == "?x"
    with pytest.raises(dataclasses.FrozenInstanceError):
        x.name = "y"
    assert x.name == "x" and Var("x") is x


def test_a_variable_made_again_after_the_last_one_went_is_equal_to_later_ones():
    made = Var("only-here").name
    gc.collect()
    again = Var(made)
    assert again == Var(made) and {again: 1}[Var(made)] == 1
    assert Literal("p", (Var(made),)) == Literal("p", (again,))


def test_programs_read_twice_share_their_variables():
    a = load_program(ROOT / "programs" / "driving.tlp")
    b = load_program(ROOT / "programs" / "driving.tlp")
    assert a.skills[0].head == b.skills[0].head
    assert all(x is y for x, y in zip(a.skills[0].head.args, b.skills[0].head.args,
                                      strict=True))


class _EverySkill(dict):
    """What the effect model bound actions to before: every primitive skill with actions."""

    def __init__(self, program):
        super().__init__()
        self.all = [s for s in program.skills if s.kind == "primitive" and s.actions]

    def get(self, shape, default=None):
        return self.all


PROGRAMS = [load_program(ROOT / "programs" / "driving.tlp"),
            load_program(ROOT / "programs" / "blocks.tlp"),
            load_program_text(blocks_with_effects())]
VALUES = st.one_of(st.sampled_from(["a", "b", "c", "ME", "NIL"]), st.integers(-2, 3),
                   st.sampled_from([0.0, 6.25, 30.0, 100.0, 2.5]))


@st.composite
def actions(draw) -> tuple[int, list[Action]]:
    """A program and actions shaped like its skills' (or not quite: another arity, an unknown
    name), with values that bind some skill or none."""
    k = draw(st.integers(0, len(PROGRAMS) - 1))
    shapes = sorted({(a.name, len(a.args)) for s in PROGRAMS[k].skills if s.kind == "primitive"
                     for a in s.actions} | {("*nothing", 1)})
    out = []
    for _ in range(draw(st.integers(1, 2))):
        name, n = draw(st.sampled_from(shapes))
        n = max(0, n + draw(st.sampled_from([0, 0, 0, 1, -1])))
        out.append(Action(name, tuple(draw(st.lists(VALUES, min_size=n, max_size=n)))))
    return k, out


@settings(max_examples=300, deadline=None)
@given(actions())
def test_actions_bound_by_shape_are_what_every_skill_gives(case):
    k, acts = case
    fast, every = Effects(PROGRAMS[k]), Effects(PROGRAMS[k])
    every._performing = _EverySkill(PROGRAMS[k])
    assert fast.of_actions(acts) == every.of_actions(acts)


def test_an_action_with_an_expression_argument_binds_no_skill():
    program = PROGRAMS[0]
    gas = next(s for s in program.skills if s.actions and s.actions[0].name == "*gas")
    expr = Action("*gas", (Expr("+", (1, 2)),) * len(gas.actions[0].args))
    assert Effects(program).of_actions([expr]) == Effects(program).of_actions([])


_ATOM = st.one_of(st.sampled_from(["A", "B"]), st.integers(-1, 2),
                  st.sampled_from([0.0, -0.0, 1.0, 2.5]))
_CHANGE = st.tuples(st.sampled_from(["insert", "delete", "replace", "add", "index"]),
                    st.sampled_from(["on", "near", ("self", ("speed",))]),
                    st.lists(st.tuples(_ATOM, _ATOM), max_size=3))


@settings(max_examples=200, deadline=None)
@given(st.lists(_CHANGE, max_size=12))
def test_a_stores_digest_text_is_a_fresh_stores_after_every_change(changes):
    store = FactStore()
    index = PerceptIndex.of_groups({"self": [["self", "ME", "speed", 1.0]]})
    for kind, rel, tuples in changes:
        have = store.get(rel)
        if kind == "insert":
            store.insert(rel, list(dict.fromkeys(t for t in tuples if t not in have)))
        elif kind == "delete":
            store.delete(rel, sorted(have, key=repr)[:len(tuples)])
        elif kind == "replace":
            store.replace(rel, tuples)
        elif kind == "add":
            store.add(rel, tuples)
        else:
            store.index(rel, (0,))
        fresh = FactStore({r: set(ts) for r, ts in store.facts.items()})
        assert store.lines(rel) == tuple(sorted(map(repr, store.get(rel))))
        assert world(index, store) == world(index, fresh)


def test_threads_making_one_name_at_once_get_one_variable():
    from concurrent.futures import ThreadPoolExecutor

    from agents.lang.core.terms import Var

    names = [f"racing{k}" for k in range(200)]
    with ThreadPoolExecutor(8) as pool:
        made = list(pool.map(lambda n: [Var(n) for _ in range(50)], names * 4))
    for k, name in enumerate(names * 4):
        assert all(v is Var(name) for v in made[k])


_GENERATED = dataclasses.make_dataclass(   # StoredStep's fields, with the generated repr
    "StoredStep", [("goal", str), ("skill", int), ("skill_name", str), ("bindings", tuple)],
    frozen=True)
_VALUE = st.one_of(st.text(max_size=4), st.integers(), st.floats(allow_nan=False))


@given(st.text(max_size=8), st.integers(), st.text(max_size=8),
       st.lists(st.tuples(st.text(max_size=3), _VALUE), max_size=4).map(tuple))
def test_a_stored_steps_text_is_the_dataclass_text(goal, skill, name, bindings):
    """The loop watch hashes the remembered paths' text (loops.intention): StoredStep's
    written-out repr is the one the dataclass would generate, so digests stay what they were."""
    assert repr(StoredStep(goal, skill, name, bindings)) == \
        repr(_GENERATED(goal, skill, name, bindings))
