"""Percept patterns are matched by a plan made once for each set of bound variables and an index
on all their bound attributes (agents/lang/core/percepts.py): on random percepts (several
percepts of one id, as a PDDL world's atoms; missing attributes; values of mixed types) and
random patterns (constants, repeated variables, the id among the attributes) bound in every
way, including variables bound to variables, it gives exactly the extensions, in exactly the
order, of the matcher it replaced (kept here as the reference), from plans made afresh and
from plans remembered."""

from __future__ import annotations

from hypothesis import example, given, settings
from hypothesis import strategies as st

from agents.lang.core import percepts
from agents.lang.core.intake import MISSING, PerceptIndex
from agents.lang.core.matcher import match_percept
from agents.lang.core.terms import Percept, PerceptPattern, Var


def old_match_percept(p: PerceptPattern, b: dict, pidx: PerceptIndex):
    """The matcher before the plans (main at ed8e5a8), word for word."""
    def subst(term, b):
        return b.get(term, term) if isinstance(term, Var) else term

    def bound(t, b):
        return not isinstance(t, Var) or t in b

    pid = subst(p.id, b)
    free = isinstance(pid, Var)
    if not free:
        cands = pidx.by_id.get((p.type, pid), ())
    else:
        key = next(((a, subst(t, b)) for a, t in p.attrs if bound(t, b)), None)
        cands = pidx.by_type.get(p.type, ()) if key is None else \
            pidx.attr_index(p.type, key[0]).get(key[1], ())
    for per in cands:
        nb = dict(b)
        if free:
            nb[pid] = per.id
        for attr, t in p.attrs:
            v = per._map.get(attr, MISSING)
            t = subst(t, nb)
            if v is MISSING or (not isinstance(t, Var) and t != v):
                break
            if isinstance(t, Var):
                nb[t] = v
        else:
            yield nb


def typed(sols: list) -> list:
    """Each extension as its (variable, value type, value) in insertion order (1, 1.0 and
    True are equal as dict values)."""
    return [[(k, type(v), v) for k, v in s.items()] for s in sols]


X, Y, Z = Var("x"), Var("y"), Var("z")
ROW_VALUES = st.sampled_from(["a", "b", 1, 1.0, 2.5])
VALUES = st.one_of(ROW_VALUES, st.just(True))   # a binding may hold what a percept may not
IDS = st.sampled_from(["_", "_", "o1", 1])
ATTRS = st.sampled_from(["arg1", "arg2"])
TERMS = st.one_of(VALUES, st.sampled_from([X, Y, Z]))


@st.composite
def rows(draw):
    """A percept row of type t or u: an id, then up to three attributes (some left out)."""
    attrs = draw(st.lists(ATTRS, unique=True, max_size=3))
    row = [draw(st.sampled_from(["t", "t", "u"])), draw(IDS)]
    for a in attrs:
        row += [a, draw(ROW_VALUES)]
    return row


@st.composite
def patterns(draw):
    attrs = draw(st.lists(st.tuples(ATTRS, TERMS), max_size=3))
    return PerceptPattern(draw(st.sampled_from(["t", "t", "u"])), draw(st.one_of(IDS, TERMS)),
                          tuple(attrs))


BINDINGS = st.dictionaries(st.sampled_from([X, Y, Z]),
                           st.one_of(VALUES, IDS, st.sampled_from([X, Y, Z, Var("w")])),
                           max_size=3)


@settings(max_examples=400, deadline=None)
@example([["t", "_", "arg1", "a", "arg2", 1], ["t", "_", "arg1", "a", "arg2", 2]],
         [(PerceptPattern("t", "_", (("arg1", "a"), ("arg2", Y))), {})], True, 0)
@given(st.lists(rows(), max_size=14), st.lists(st.tuples(patterns(), BINDINGS), min_size=1,
                                                max_size=6),
       st.booleans(), st.integers(0, 12))
def test_plans_match_as_the_plain_matcher(rs, queries, as_groups, few):
    was, percepts._FEW = percepts._FEW, few   # narrow by the index from any number of candidates
    try:
        for fresh in (True, False):
            if fresh:
                percepts._PVARS.clear()
            groups: dict = {}
            for r in rs:
                groups.setdefault(r[0], []).append(r)
            pidx = PerceptIndex.of_groups(groups) if as_groups else \
                PerceptIndex([Percept.from_list(r) for r in rs])
            ref = PerceptIndex.of_groups(groups) if as_groups else \
                PerceptIndex([Percept.from_list(r) for r in rs])
            for p, b in queries:
                got = list(match_percept(p, dict(b), pidx))
                want = list(old_match_percept(p, dict(b), ref))
                assert typed(got) == typed(want), (p, b, rs)   # values, types, key order
    finally:
        percepts._FEW = was
