"""Each kind's compiled field checks (bus/compiled.py) accept and refuse exactly what the
field-by-field walk does: the same values for a good wire map, the same error (key, kind,
field path, what is wrong) for a spoilt one, over random valid messages of every kind with one
field spoilt, dropped, or left alone."""

from __future__ import annotations

import copy
import math

import msgpack
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_codec import MESSAGES

from bus.codec import _compiled, check_fields, walk_fields
from bus.errors import CodecError
from bus.messages import ProcessStats
from bus.rows import unpack_rows

EDGES = [   # just past the bounds the kinds' specs draw
    math.nan, math.inf, -math.inf, 2**64, -(2**63) - 1, -1, 0, 1.5, True, "", "post", "done",
    "x" * 257, "x" * 33, {}, [], [[]], [[1]], [["self", math.nan]], [["a", True]],
    {"model": [[1]]}, {"model": [], "scs": []}, {"name": 1}, {"ok": "yes"},
    [{"action": [], "status": "done", "reason": ""}], {"ME": [{"action": ["a"]}]},
    [{"id": "", "goal": "g", "priority": 1, "status": "s"}], {"a": {"b": {"c": {"d": {}}}}}]
junk_atoms = st.one_of(
    st.none(), st.booleans(), st.integers(), st.floats(), st.text(max_size=300),
    st.binary(max_size=4))
nested = st.recursive(junk_atoms, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.one_of(st.text(max_size=4), st.integers()),
                                                 inner, max_size=4)), max_leaves=10)
junk = st.one_of(st.sampled_from(EDGES), junk_atoms, nested)


def outcome(fn, *args):
    """('ok', values) or ('refused', the error's text)."""
    try:
        return "ok", fn(*args)
    except CodecError as exc:
        return "refused", str(exc)


@settings(max_examples=600, deadline=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(which=st.sampled_from(sorted(MESSAGES)), data=st.data(),
       how=st.sampled_from(["valid", "edges", "spoilt", "dropped"]))
def test_compiled_checks_agree_with_the_walk(which, data, how) -> None:
    key_fn, strategy = MESSAGES[which]
    msg = data.draw(strategy)
    cls = type(msg)
    kind = _compiled(cls)
    body = msgpack.unpackb(msgpack.packb({n: getattr(msg, n) for n in kind.names},
                                         use_bin_type=True), raw=False)
    name = data.draw(st.sampled_from(kind.names))
    key = key_fn()
    if how == "edges":   # every edge value in turn in one field
        for value in EDGES:
            agree(key, cls, {**body, name: value}, complete=True)
        return
    if how == "spoilt":
        body[name] = data.draw(junk)
    elif how == "dropped":
        del body[name]
    walked = agree(key, cls, body, complete=how != "dropped")
    if how == "valid":
        assert walked[0] == "ok"


def agree(key: str, cls: type, body: dict, complete: bool) -> tuple:
    """Checks ``body`` both ways; asserts they agree, gives the walk's outcome."""
    kind = _compiled(cls)
    walked = outcome(walk_fields, key, kind, copy.deepcopy(body))
    compiled = outcome(check_fields, key, cls, copy.deepcopy(body))
    assert compiled == walked
    if complete:   # every field there: the compiled function itself decided
        assert outcome(kind.check, key, copy.deepcopy(body), unpack_rows) == walked
    return walked


def test_a_spoilt_field_is_named_with_the_key() -> None:
    key_fn, _ = MESSAGES["stats"]
    kind = _compiled(ProcessStats)
    body = {"process": "ME.inference", "compute_ms": math.nan, "late": 0}
    assert outcome(kind.check, key_fn(), body, unpack_rows) == (
        "refused", f"{key_fn()}: ProcessStats.compute_ms: expected a number >= 0, got nan")
