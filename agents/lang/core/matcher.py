"""Dict-binding matcher used by the executive and goal expansion (small, explainable joins):
percept patterns, concept literals (with negation: unbound variables inside ``not`` are
existential) and tests, solved left to right with tests/negations delayed until bound."""

from __future__ import annotations

from collections.abc import Iterator
from itertools import islice

from .arith import compile_test
from .percepts import match_percept, subst
from .store import FactStore, PerceptIndex
from .terms import Literal, PerceptPattern, Test, Var, sort_key

_TESTS: dict[int, object] = {}
_PICKS: dict[tuple, tuple] = {}  # (ids of the conditions, bound variables) -> (first, rest, conds)
MAX_PICKS = 4096  # orders kept (cleared when full: a program's skills need a few hundred)


def ground(lit: Literal, b: dict) -> Literal:
    """``lit`` with bound variables replaced (unbound ones stay Vars)."""
    return Literal(lit.pred, tuple(subst(a, b) for a in lit.args), lit.negated, lit.loc)


def match_fact(lit: Literal, b: dict, store: FactStore) -> Iterator[dict]:
    """Extensions of ``b`` under which positive ``lit`` is a fact in ``store``."""
    args = [subst(a, b) for a in lit.args]
    pos = tuple(i for i, a in enumerate(args) if not isinstance(a, Var))
    if len(pos) == len(args):
        if tuple(args) in store.get(lit.pred):
            yield b
        return
    cands = store.index(lit.pred, pos).get(tuple(args[i] for i in pos), ()) if pos \
        else store.get(lit.pred)
    for t in cands:
        nb = dict(b)
        ok = True
        for i, a in enumerate(args):
            if isinstance(a, Var):
                if a in nb and nb[a] != t[i]:
                    ok = False
                    break
                nb[a] = t[i]
        if ok:
            yield nb


def holds(lit: Literal, b: dict, store: FactStore) -> bool:
    """True if some fact matches ``lit`` (unbound variables existential; its sign is not
    read)."""
    args = lit.args
    if not b and not any(isinstance(a, Var) for a in args):   # a ground literal: one lookup
        return tuple(args) in store.get(lit.pred)
    return next(match_fact(lit, b, store), None) is not None


def test_holds(t: Test, b: dict) -> bool:
    fn = _TESTS.get(id(t.expr))
    if fn is None:
        fn = _TESTS[id(t.expr)] = (compile_test(t.expr, lambda v: v), t.expr)
    return fn[0](b)


def ready(cond: object, b: dict) -> bool:
    """Tests may run once all their variables are bound; everything else at once."""
    return not isinstance(cond, Test) or all(v in b for v in cond.variables())


def step(cond: object, b: dict, pidx: PerceptIndex, store: FactStore) -> Iterator[dict]:
    """Extensions of ``b`` satisfying one condition."""
    if isinstance(cond, PerceptPattern):
        yield from match_percept(cond, b, pidx)
    elif isinstance(cond, Test):
        # a test some variable of which nothing bound cannot hold (a solver's candidate
        # binding whose relation matched no belief leaves it open): no extension
        if ready(cond, b) and test_holds(cond, b):
            yield b
    elif cond.negated:
        if not holds(cond, b, store):
            yield b
    else:
        yield from match_fact(cond, b, store)


def solve(conds: list, b: dict, pidx: PerceptIndex, store: FactStore) -> Iterator[dict]:
    """All extensions of ``b`` satisfying every condition. The most constrained condition goes
    first (bound tests and negations, fully bound literals, percepts by id, ...)."""
    if not conds:
        yield b
        return
    # which condition goes first depends only on the conditions and on which variables are
    # bound, not on their values: chosen once per such pair (the entry holds the conditions,
    # so the ids in its key stay theirs)
    if len(conds) == 1:
        cond, rest = conds[0], ()
    else:
        key = (*map(id, conds), frozenset(b))
        got = _PICKS.get(key)
        if got is None:
            if len(_PICKS) >= MAX_PICKS:
                _PICKS.clear()
            i = _pick(conds, b)
            got = _PICKS[key] = (conds[i], (*conds[:i], *conds[i + 1:]), tuple(conds))
        cond, rest = got[0], got[1]
    # a percept or a positive literal straight from its matcher, and the last condition's
    # extensions without a further generator: the same extensions through fewer frames
    ext = match_percept(cond, b, pidx) if cond.__class__ is PerceptPattern else \
        match_fact(cond, b, store) if cond.__class__ is Literal and not cond.negated else \
        step(cond, b, pidx, store)
    if not rest:
        yield from ext
        return
    for nb in ext:
        yield from solve(rest, nb, pidx, store)


def _bound(t: object, b: dict) -> bool:
    return not isinstance(t, Var) or t in b


def _score(c: object, b: dict, conds: list) -> int:
    if isinstance(c, Test):
        return 100 if ready(c, b) else -1
    if isinstance(c, PerceptPattern):
        if _bound(c.id, b):
            return 70
        return 40 if any(_bound(t, b) for _, t in c.attrs) else 10
    if c.negated:
        return 90 if _neg_ready(c, b, conds) else -1
    nb = sum(1 for a in c.args if _bound(a, b))
    if nb == len(c.args):
        return 80
    return 50 + nb if nb else 5


def _pick(conds: list, b: dict) -> int:
    best, best_score = 0, -2
    for k, c in enumerate(conds):
        sc = _score(c, b, conds)
        if sc > best_score:
            best, best_score = k, sc
            if sc >= 100:
                break
    return best


def _neg_ready(c: Literal, b: dict, conds: list) -> bool:
    """A negation waits until variables that other positive conditions bind are bound."""
    for o in conds:
        if o is c or isinstance(o, Test) or getattr(o, "negated", False):
            continue
        if any(v not in b for v in c.variables() & o.variables()):
            return False
    return True


def first_failure(conds: list, b: dict, pidx: PerceptIndex, store: FactStore):
    """(condition, bindings, several) for the first condition (in written order) after which no
    extension of ``b`` exists, or None when all hold. ``bindings`` are those of the conditions
    before it when they have one solution; when they have several (``several`` is True) they are
    ``b`` itself, so explanations never depend on hashing or on which match came first."""
    last, several = b, False
    for k in range(1, len(conds) + 1):
        sols = list(islice(solve(conds[:k], b, pidx, store), 2))
        if not sols:
            return conds[k - 1], last, several
        several = several or len(sols) > 1
        last = b if several else sols[0]
    return None


def binding_key(b: dict) -> tuple:
    """Deterministic order of bindings (by variable name, then value)."""
    return tuple((v.name, sort_key(x)) for v, x in sorted(b.items(), key=lambda kv: kv[0].name))


def unify_head(head: Literal, goal: Literal, b: dict | None = None) -> dict | None:
    """Bind a clause head's variables to a goal's constants (extending `b`); None on a clash.
    Goal variables match anything and bind nothing (seed 000: goals may hold variables)."""
    b = {} if b is None else b
    for h, g in zip(head.args, goal.args, strict=True):
        if isinstance(g, Var):
            continue
        if isinstance(h, Var):
            if h in b and b[h] != g:
                return None
            b[h] = g
        elif h != g:
            return None
    return b
