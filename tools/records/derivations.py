"""Why a concept instance is false, or true, on one cycle's percepts and beliefs: for each
clause of its concept, the first condition (in written order) that fails and what makes it
fail, or one derivation of it; with the engine's own explainable matcher
(agents/lang/core/matcher.py: ``solve`` and ``first_failure``, which the executive uses to
say why a skill was passed over) and its way of showing a condition
(agents/lang/execution/paths.py ``show``).

Here, under the web view's beliefs panel (tools/view/beliefs.py) and `teleo why`
(tools/records/why.py) alike, which both ask it.
"""

from __future__ import annotations

from itertools import islice
from typing import Any

from agents.lang import Literal, PerceptPattern, Program, Test, Var
from agents.lang.core.intake import PerceptIndex
from agents.lang.core.matcher import (
    binding_key,
    first_failure,
    ground,
    match_fact,
    solve,
    unify_head,
)
from agents.lang.core.store import FactStore
from agents.lang.execution.paths import show

MAX_DEPTH = 3       # levels of "because" followed below a goal's clause
MAX_SHOWN = 6       # beliefs (or percepts) listed for one condition
MAX_SOLUTIONS = 50  # matches looked at to pick the first derivation of a belief


def why_false(program: Program, lit: Literal, pidx: PerceptIndex, store: FactStore,
              depth: int = 0) -> list[dict[str, Any]]:
    """One entry per clause of ``lit``'s concept whose head matches it: the first condition
    (in written order) that fails, and what makes it fail: the beliefs that hold under a
    ``not`` (each with the percepts behind it), the clauses of a missing belief (down to
    MAX_DEPTH), the percepts seen of an object whose pattern does not match, a test's values."""
    out = []
    for clause in program.concepts.get(lit.pred, ()):
        b = unify_head(clause.head, lit, {})
        if b is None:
            continue
        conds = [*clause.percepts, *clause.relations, *clause.tests]
        entry: dict[str, Any] = {"clause": f"{lit.pred}#{clause.index}",
                                 "where": str(clause.loc or "")}
        failed = first_failure(conds, b, pidx, store)
        if failed is None:
            out.append({**entry, "kind": "holds", "cond": "",
                        "note": "every condition holds on the recorded beliefs"})
            continue
        cond, fb, several = failed
        entry.update(cond=show(cond, fb), every=several)
        out.append({**entry, **_failure(program, cond, fb, pidx, store, depth)})
    return out


def _failure(program: Program, cond: object, b: dict, pidx: PerceptIndex, store: FactStore,
             depth: int) -> dict[str, Any]:
    """What makes one condition fail under bindings ``b``."""
    if isinstance(cond, PerceptPattern):
        return {"kind": "unseen", "seen": percepts_seen(cond, b, pidx)}
    if isinstance(cond, Test):
        return {"kind": "test", "values": values(cond.variables(), b)}
    if cond.negated:
        found = matching(cond, b, store)
        return {"kind": "negated", "because": [why_holds(program, f, pidx, store)
                                               for f in found[:MAX_SHOWN]],
                "more": max(0, len(found) - MAX_SHOWN)}
    missing = ground(cond, b)
    below = why_false(program, missing, pidx, store, depth + 1) \
        if depth + 1 < MAX_DEPTH and missing.pred in program.concepts else []
    return {"kind": "missing", "below": below}


def why_holds(program: Program, lit: Literal, pidx: PerceptIndex,
              store: FactStore) -> dict[str, Any]:
    """A belief that holds, with one derivation: the first clause (and its first match, in a
    deterministic order) that gives it, its percepts and relations under that match."""
    for clause in program.concepts.get(lit.pred, ()):
        b = unify_head(clause.head, lit, {})
        if b is None:
            continue
        conds = [*clause.percepts, *clause.relations, *clause.tests]
        sols = list(islice(solve(conds, b, pidx, store), MAX_SOLUTIONS))
        if sols:
            sol = min(sols, key=binding_key)
            return {"belief": str(lit), "clause": f"{lit.pred}#{clause.index}",
                    "percepts": [show(p, sol) for p in clause.percepts],
                    "relations": [show(r, sol) for r in clause.relations]}
    return {"belief": str(lit), "clause": "", "percepts": [], "relations": [],
            "note": "no clause of the program derives it from this cycle's percepts "
                    "(a fact of the agent's world model, or another program)"}


def matching(cond: Literal, b: dict, store: FactStore) -> list[Literal]:
    """The beliefs matching ``cond`` (as a positive literal) under ``b``, sorted."""
    pos = Literal(cond.pred, cond.args)
    found = {binding_key(nb): ground(pos, nb) for nb in match_fact(pos, b, store)}
    return [found[k] for k in sorted(found)]


def percepts_seen(p: PerceptPattern, b: dict, pidx: PerceptIndex) -> list[str]:
    """This cycle's percepts of the pattern's object (its type and, when bound, its id)."""
    pid = b.get(p.id, p.id) if isinstance(p.id, Var) else p.id
    rows = pidx.by_type.get(p.type, ()) if isinstance(pid, Var) else \
        pidx.by_id.get((p.type, pid), ())
    return [str(r) for r in list(rows)[:MAX_SHOWN]]


def values(variables: set, b: dict) -> dict[str, Any]:
    return {v.name: b[v] for v in sorted(variables, key=lambda v: v.name) if v in b}

