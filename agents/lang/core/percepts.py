"""Matching a percept pattern against one cycle's percepts (the matcher's ``match_percept``,
agents/lang/core/matcher.py). How a pattern is matched depends only on which of its variables
are bound, so it is worked out once for each (``_plan``); a candidate's bound attributes are
compared before its bindings are copied, and many candidates are narrowed by an index on all
the bound attributes at once. The extensions, and their order, are those of the plain matcher
(``_match_any``, which still serves a variable bound to a variable): tests/lang/test_percepts.py
holds the two to each other."""

from __future__ import annotations

from collections.abc import Iterator

from .intake import MISSING, PerceptIndex
from .terms import PerceptPattern, Var

MAX_PLANS = 4096  # plans kept (cleared when full)
_PVARS: dict[int, tuple] = {}   # id of a percept pattern -> (pattern, its variables, plans)
_FEW = 8  # candidates filtered one by one; more are looked up by all their bound attributes


def subst(term: object, b: dict) -> object:
    """``term`` with bound variables replaced by their values."""
    return b.get(term, term) if isinstance(term, Var) else term


def match_percept(p: PerceptPattern, b: dict, pidx: PerceptIndex) -> Iterator[dict]:
    """Extensions of ``b`` matching pattern ``p`` against one percept each, in the order of
    the candidates (those of the id, else of the first attribute bound, else of the type).
    How ``p`` is matched from the variables ``b`` binds is worked out once (``_plan``):
    a candidate's bound attributes are compared before its bindings are copied."""
    got = _PVARS.get(id(p))
    if got is None or got[0] is not p:
        got = _pattern_vars(p)
    mask = tuple(map(b.__contains__, got[1]))
    plan = got[2].get(mask)
    if plan is None:
        plan = got[2][mask] = _plan(p, b, got[1])
    pid, key_attr, key_term, fixed, rest, bound, fixed_vars = plan
    if bound:
        for v in bound:   # a variable bound to a variable: the general matcher (rare)
            if isinstance(b[v], Var):
                yield from _match_any(p, b, pidx)
                return
    free = pid is MISSING
    if not free:
        idv = b[pid] if isinstance(pid, Var) else pid
        cands = pidx.by_id.get((p.type, idv), ())
    elif key_attr is None:
        cands = pidx.by_type.get(p.type, ())
    else:
        cands = pidx.attr_index(p.type, key_attr).get(
            b[key_term] if isinstance(key_term, Var) else key_term, ())
    fx = [(a, b[t]) if isinstance(t, Var) else (a, t) for a, t in fixed] if fixed_vars \
        else fixed
    if len(cands) > _FEW and (len(fx) > 1 or fx and not free):   # by all at once
        cands = _by_attrs(pidx, p.type, fx, cands, () if free else (idv,))
    pvar = p.id
    for per in cands:
        m = per._map
        for a, t in fx:
            v = m.get(a, MISSING)
            if v is MISSING or t != v:
                break
        else:
            nb = dict(b)
            if free:
                nb[pvar] = per.id
            for a, t in rest:
                v = m.get(a, MISSING)
                if v is MISSING:
                    break
                if t in nb:
                    if nb[t] != v:
                        break
                else:
                    nb[t] = v
            else:
                yield nb


def _by_attrs(pidx: PerceptIndex, type_: str, fx: list, cands: list, key: tuple) -> list:
    """The percepts of ``cands`` (all those of ``type_`` with the id ``key`` holds, or when it
    is empty with the first value ``fx`` binds) that have every value ``fx`` binds, by an index
    on all of them; their order kept (both lists keep the order of ``by_type``); ``cands``
    where there can be no index."""
    ix = pidx.attrs_index(type_, tuple([a for a, _ in fx]), bool(key))
    if ix is None:
        return cands
    try:
        return ix.get((*key, *[t for _, t in fx]), ())
    except TypeError:   # an unhashable value
        return cands


def _pattern_vars(p: PerceptPattern) -> tuple:
    """(p, its distinct variables in written order, its plans by which of them are bound),
    kept."""
    if len(_PVARS) >= MAX_PLANS:
        _PVARS.clear()
    vs = tuple(dict.fromkeys(t for t in (p.id, *(t for _, t in p.attrs)) if isinstance(t, Var)))
    got = _PVARS[id(p)] = (p, vs, {})
    return got


def _plan(p: PerceptPattern, b: dict, pvars: tuple) -> tuple:
    """How ``p`` is matched when the variables of it that ``b`` binds are bound: (the id
    (MISSING when free), the attribute whose index gives the candidates and its term, the
    (attr, term) pairs compared before copying, the (attr, variable) pairs bound or compared
    after, the variables of ``p`` bound in ``b``, whether a compared term is a variable)."""
    bound = tuple(v for v in pvars if v in b)
    pid = MISSING if isinstance(p.id, Var) and p.id not in b else p.id
    first = next(((a, t) for a, t in p.attrs if not isinstance(t, Var) or t in b), (None, None))
    fixed = tuple((a, t) for a, t in p.attrs if not isinstance(t, Var) or t in b)
    rest = tuple((a, t) for a, t in p.attrs if isinstance(t, Var) and t not in b)
    return (pid, *first, fixed, rest, bound, any(isinstance(t, Var) for _, t in fixed))


def _match_any(p: PerceptPattern, b: dict, pidx: PerceptIndex) -> Iterator[dict]:
    """``match_percept`` for any bindings, variables bound to variables included."""
    pid = subst(p.id, b)
    free = isinstance(pid, Var)
    if not free:
        cands = pidx.by_id.get((p.type, pid), ())
    else:
        key = next(((a, subst(t, b)) for a, t in p.attrs if not isinstance(t, Var) or t in b), None)
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
