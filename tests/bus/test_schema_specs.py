"""The field specs (bus/schema/): any value is either accepted as it is or refused with a
FieldError naming where in it the problem is; what is accepted is what the readers rely on
(hypothesis properties against plain oracles), and a refusal's message stays short."""

from __future__ import annotations

import json
import math
import string

import msgpack
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bus.schema import (
    Atom,
    FieldError,
    Int,
    ListOf,
    MapOf,
    Num,
    OneOf,
    Plain,
    Record,
    Str,
    Tagged,
    TupleOf,
    brief,
)

atoms = st.one_of(st.none(), st.booleans(), st.integers(-(2**70), 2**70), st.floats(),
                  st.text(max_size=6), st.binary(max_size=3))
anything = st.recursive(atoms, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.one_of(st.text(max_size=4),
                                                           st.integers(0, 3)), inner,
                                                 max_size=4)), max_leaves=20)
SETTINGS = settings(max_examples=300, deadline=None, suppress_health_check=list(HealthCheck))


def finite_number(v) -> bool:
    return type(v) in (int, float) and math.isfinite(v)


@SETTINGS
@given(anything, st.floats(-100, 100), st.floats(0, 100))
def test_num_takes_finite_numbers_in_range_and_nothing_else(v, lo, width):
    spec = Num(lo, lo + width)
    ok = finite_number(v) and lo <= v <= lo + width
    if ok:
        assert spec.check(v) is v
    else:
        with pytest.raises(FieldError, match=r"^expected a number in \["):
            spec.check(v)


@SETTINGS
@given(anything)
def test_int_str_and_atom_take_their_own_type_only(v):
    assert _fits(Int(-5, 5), v) == (type(v) is int and -5 <= v <= 5)
    assert _fits(Str(max_len=3), v) == (type(v) is str and len(v) <= 3)
    assert _fits(Atom(), v) == (type(v) is str or (type(v) in (int, float) and
                                                   finite_number(v)))
    assert _fits(OneOf(("a", 1)), v) == (type(v) in (str, int) and v in ("a", 1)
                                         and type(v) is not bool)


def _fits(spec, v) -> bool:
    try:
        spec.check(v)
    except FieldError:
        return False
    return True


CAR = Record({"id": Str(), "x": Num(-10, 10)}, {"speed": Num(0, 5)})


@SETTINGS
@given(st.dictionaries(st.sampled_from(["id", "x", "speed", "colour", ""]), anything,
                       max_size=4))
def test_a_record_accepts_exactly_its_fields_and_names_the_one_it_refuses(d):
    want = {"id", "x"} <= set(d) and set(d) <= {"id", "x", "speed"} and \
        type(d["id"]) is str and finite_number(d["x"]) and -10 <= d["x"] <= 10 and \
        ("speed" not in d or finite_number(d["speed"]) and 0 <= d["speed"] <= 5)
    try:
        assert CAR.check(d) is d and want
    except FieldError as exc:
        assert not want
        named = exc.path[0] if exc.path else exc.problem.split("'")[1]
        assert named in (*d, "id", "x"), str(exc)
        assert str(exc).startswith(exc.where)


EVENTS = Tagged({"block": Record({"segment": Str()}), "go": Record({}, {"to": ListOf(Int())})})


@SETTINGS
@given(anything)
def test_a_tagged_map_is_refused_by_its_kind_or_a_field_of_that_kind(v):
    try:
        EVENTS.check(v)
    except FieldError as exc:
        text = str(exc)
        assert text.startswith(("expected a map", "kind:", "unknown kind", "segment", "to",
                                "unknown field")), text
    else:
        assert v["kind"] in ("block", "go")


def _plain_oracle(v, depth=0) -> bool:
    if depth > 6:
        return False
    if type(v) is dict:
        return all(type(k) is str and _plain_oracle(x, depth + 1) for k, x in v.items())
    if type(v) is list:
        return all(_plain_oracle(x, depth + 1) for x in v)
    if type(v) is float:
        return math.isfinite(v)
    if type(v) is int:
        return -(2**63) <= v <= 2**64 - 1
    return type(v) in (str, bool, type(None))


@SETTINGS
@given(anything)
def test_plain_data_is_what_msgpack_and_json_can_both_carry(v):
    spec = Plain(max_depth=6, top=None)
    ok = _plain_oracle(v)
    assert _fits(spec, v) == ok
    if ok:
        assert msgpack.unpackb(msgpack.packb(v), strict_map_key=False) == v or v != v
        json.dumps(v, allow_nan=False)


def test_plain_data_names_the_first_value_that_is_not():
    spec = Plain(max_depth=4)
    for value, where in (({"a": [1, b"x"]}, "a[1]: expected plain data"),
                         ({"a": {"b": math.nan}}, "a.b: expected plain data"),
                         ({"a": [[[[1]]]]}, "a[0][0][0]: nested deeper than 4 levels"),
                         ({"a": 2**64}, "a: expected plain data"),
                         ({"odd key": "\ud800"}, "['odd key']: expected plain data")):
        with pytest.raises(FieldError) as info:
            spec.check(value)
        assert str(info.value).startswith(where), str(info.value)


@SETTINGS
@given(anything)
def test_a_shown_value_is_short_however_large_or_deep(v):
    for _ in range(3000):
        v = [v]
    assert len(brief(v)) <= 90 and len(brief("x" * 10**6)) <= 100


def test_paths_read_as_the_message_does():
    spec = Record({"cars": ListOf(Record({"x": Num(0, 1)})), "size": TupleOf(Num(), Num()),
                   "counters": MapOf(MapOf(Int()))})
    cases = [({"cars": [{"x": 0}, {"x": 2}], "size": [1, 1], "counters": {}},
              "cars[1].x: expected a number in [0, 1], got 2"),
             ({"cars": [], "size": [1, "w"], "counters": {}},
              "size[1]: expected a finite number, got 'w'"),
             ({"cars": [], "size": [1, 1], "counters": {"ME": {"hits": 1.5}}},
              "counters.ME.hits: expected an integer, got 1.5"),
             ({"cars": [], "size": [1, 1], "counters": {"a b": {"k": None}}},
              "counters['a b'].k: expected an integer, got None"),
             ({"cars": [], "size": [1, 1]}, "counters: missing; expected a map")]
    for value, message in cases:
        with pytest.raises(FieldError) as info:
            spec.check(value)
        assert str(info.value) == message


def test_a_long_string_is_refused_saying_its_length():
    with pytest.raises(FieldError, match=r"expected a name of at most 8 characters, got 'x+'"
                                         r"\.\.\. \(100 characters\)"):
        Str(8, what="a name").check("x" * 100)
    assert set(string.ascii_letters) <= set(Str(what="a name", pattern=r"[A-Za-z]+").check(
        string.ascii_letters))
