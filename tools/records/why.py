"""Why a concept instance is or is not believed at one cycle (`teleo why`, issue 34; as Soar's
`matches`): the cycle's percepts (and the agent's world model, the facts its SCS bodies
asserted) go through the engine's inference (Engine.infer) for the beliefs, and each clause of
the concept is matched against them with the engine's own explainable matcher
(agents/lang/core/matcher.py: ``solve`` and ``first_failure``, which the executive uses to say
why a skill was passed over), conditions shown as the executive shows them
(agents/lang/execution/paths.py ``show``).

For a believed instance: each clause that holds, with its bindings and, for each condition,
what matched it (the percept, the belief, or no belief for a `not`). For one not believed:
each clause's first condition (in written order) that no binding satisfies, and what was
there instead: the percepts of that type, the beliefs of that concept, the beliefs that a
`not` found, or a test's values.
"""

from __future__ import annotations

from typing import Any

from agents.lang import Engine, Literal, PerceptPattern, Program, Test
from agents.lang.core.intake import PerceptIndex
from agents.lang.core.matcher import binding_key, first_failure, ground, solve, subst, unify_head
from agents.lang.core.store import store_of
from agents.lang.core.terms import Var, sort_key
from agents.lang.engine import as_percepts
from agents.lang.execution.paths import show

NEAREST = 5  # things shown as "there instead"


def _plain(b: dict) -> dict[str, str]:
    return {str(v): str(x) for v, x in sorted(b.items(), key=lambda kv: kv[0].name)}


def _percepts_like(p: PerceptPattern, b: dict, pidx: PerceptIndex) -> list[str]:
    """The percepts of ``p``'s object when its id is bound, else of its type; sorted."""
    pid = subst(p.id, b)
    found = pidx.by_id.get((p.type, pid), ()) if not isinstance(pid, Var) else ()
    found = found or pidx.by_type.get(p.type, ())
    return [str(x) for x in sorted(found, key=lambda x: sort_key(x.id))][:NEAREST]


def _beliefs_like(lit: Literal, b: dict, store: Any) -> list[str]:
    """Beliefs of ``lit``'s concept, those agreeing with its bound arguments first."""
    args = [subst(a, b) for a in lit.args]
    rows = sorted(store.get(lit.pred), key=lambda t: (
        -sum(1 for a, v in zip(args, t, strict=False) if not isinstance(a, Var) and a == v),
        [sort_key(v) for v in t]))
    return [str(Literal(lit.pred, tuple(t))) for t in rows[:NEAREST]]


def _matched(cond: object, b: dict, pidx: PerceptIndex, store: Any) -> str:
    """What satisfied ``cond`` under the full binding ``b``."""
    if isinstance(cond, PerceptPattern):
        hits = pidx.by_id.get((cond.type, subst(cond.id, b)), ())
        return f"percept {hits[0]}" if hits else "percept"
    if isinstance(cond, Test):
        return "holds"
    if cond.negated:
        return f"no belief matches {ground(Literal(cond.pred, cond.args), b)}"
    return f"belief {ground(cond, b)}"


def _instead(cond: object, b: dict, pidx: PerceptIndex, store: Any) -> list[str]:
    """What was there in place of the failed ``cond`` (bindings ``b`` of those before it)."""
    if isinstance(cond, PerceptPattern):
        return [f"percept {x}" for x in _percepts_like(cond, b, pidx)] or \
            [f"no percept of type {cond.type}"]
    if isinstance(cond, Test):
        values = {str(v): str(b[v]) for v in sorted(cond.variables(), key=str) if v in b}
        return [f"{k} = {v}" for k, v in values.items()] or ["its variables are unbound"]
    if cond.negated:
        positive = Literal(cond.pred, cond.args)
        rows = [ground(positive, nb) for nb in solve([positive], b, pidx, store)]
        return [f"belief {x}" for x in sorted({str(r) for r in rows})[:NEAREST]]
    return [f"belief {x}" for x in _beliefs_like(cond, b, store)] or \
        [f"no belief of {cond.pred}"]


def _clause(clause: Any, lit: Literal, pidx: PerceptIndex, store: Any) -> dict[str, Any]:
    """One clause of ``lit``'s concept matched: holds (with what matched each condition) or
    its first failing condition and what was there instead."""
    where = f"{clause.loc.source}:{clause.loc.line}:{clause.loc.col}" if clause.loc else ""
    out: dict[str, Any] = {"clause": f"{clause.head} #{clause.index}", "at": where}
    b0 = unify_head(clause.head, lit, {})
    if b0 is None:
        return {**out, "holds": False, "failed": f"head {clause.head} does not match {lit}",
                "instead": []}
    conds = [*clause.percepts, *clause.relations, *clause.tests]
    sols = sorted(solve(conds, b0, pidx, store), key=binding_key)
    if sols:
        b = sols[0]
        return {**out, "holds": True, "bindings": _plain(b), "solutions": len(sols),
                "conditions": [{"condition": show(c, {}) if isinstance(c, Test) else str(c),
                                "matched": _matched(c, b, pidx, store),
                                "as": show(c, b)} for c in conds]}
    cond, b, several = first_failure(conds, b0, pidx, store)
    return {**out, "holds": False, "failed": show(cond, b), "bindings": _plain(b),
            "several": several, "instead": _instead(cond, b, pidx, store)}


def why(program: Program, lit: Literal, percepts: list, model: list) -> dict[str, Any]:
    """The report on ``lit`` (a concept instance) for one cycle's ``percepts`` (neutral lists)
    and world ``model`` (asserted facts): believed, and each clause matched."""
    engine = Engine(program)
    pidx = PerceptIndex(as_percepts(percepts))
    beliefs = engine.infer(pidx, model)
    store = store_of(beliefs)
    believed = any(True for _ in solve([Literal(lit.pred, lit.args)], {}, pidx, store))
    asserted = any(list(row[:1]) == [lit.pred] and unify_head(lit, Literal(
        lit.pred, tuple(row[1:]))) is not None for row in map(tuple, model)
        if len(row) == len(lit.args) + 1)
    return {"instance": str(lit), "believed": believed, "asserted": asserted,
            "clauses": [_clause(c, lit, pidx, store) for c in program.concepts.get(lit.pred, ())]}


def why_text(report: dict[str, Any], where: str) -> str:
    """The report for a person (``where``: "at cycle N of run R (agent A)")."""
    verdict = "believed" if report["believed"] else "not believed"
    lines = [f"{report['instance']} {where}: {verdict}"]
    if report["asserted"]:
        lines.append("  asserted in the agent's world model (a fact an SCS body asserted)")
    if not report["clauses"] and not report["asserted"]:
        lines.append("  no clause defines it (a predicate only SCS bodies assert)")
    for c in report["clauses"]:
        at = f" ({c['at']})" if c["at"] else ""
        if c["holds"]:
            binds = ", ".join(f"{k}={v}" for k, v in c["bindings"].items())
            more = f"; {c['solutions']} bindings, the first shown" if c["solutions"] > 1 else ""
            lines.append(f"  clause {c['clause']}{at} holds with {binds or 'no bindings'}{more}:")
            width = max(len(x["as"]) for x in c["conditions"]) if c["conditions"] else 0
            lines += [f"    {x['as']:<{width}}  <- {x['matched']}" for x in c["conditions"]]
        else:
            every = " (for every binding of the conditions before it)" if c.get("several") \
                else ""
            lines.append(f"  clause {c['clause']}{at} fails at {c['failed']}{every}")
            lines += [f"    there instead: {x}" for x in c["instead"]]
    return "\n".join(lines)
