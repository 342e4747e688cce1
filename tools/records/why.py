"""Why a concept instance is or is not believed at one cycle (`teleo why`; as Soar's
`matches`): the cycle's percepts (and the agent's world model, the facts its SCS bodies
asserted) go through the engine's inference (Engine.infer) for the beliefs, and each clause of
the concept is matched against them with the engine's own explainable matcher
(agents/lang/core/matcher.py ``solve``; the failures through tools/records/derivations.py,
which the web view's beliefs panel uses too).

For a believed instance: each clause that holds, with its bindings and, for each condition,
what matched it (the percept, the belief, or no belief for a `not`). For one not believed:
each clause's first condition (in written order) that no binding satisfies, and what was
there instead: the percepts seen of that object, a test's values, the beliefs that a `not`
found (each with its own derivation), or, for a missing belief, why that one is false in turn.
"""

from __future__ import annotations

from typing import Any

from agents.lang import Engine, Literal, PerceptPattern, Program, Test
from agents.lang.core.intake import PerceptIndex
from agents.lang.core.matcher import binding_key, ground, solve, subst, unify_head
from agents.lang.core.store import store_of
from agents.lang.engine import as_percepts
from agents.lang.execution.paths import show
from tools.records.derivations import why_false


def _plain(b: dict) -> dict[str, str]:
    return {str(v): str(x) for v, x in sorted(b.items(), key=lambda kv: kv[0].name)}


def _matched(cond: object, b: dict, pidx: PerceptIndex) -> str:
    """What satisfied ``cond`` under the full binding ``b``."""
    if isinstance(cond, PerceptPattern):
        hits = pidx.by_id.get((cond.type, subst(cond.id, b)), ())
        return f"percept {hits[0]}" if hits else "percept"
    if isinstance(cond, Test):
        return "holds"
    if cond.negated:
        return f"no belief matches {ground(Literal(cond.pred, cond.args), b)}"
    return f"belief {ground(cond, b)}"


def _holds(clause: Any, lit: Literal, pidx: PerceptIndex, store: Any) -> dict[str, Any] | None:
    """A clause of ``lit``'s concept that holds: its first binding (in a deterministic order)
    and what matched each condition; None when it does not hold."""
    b0 = unify_head(clause.head, lit, {})
    conds = [*clause.percepts, *clause.relations, *clause.tests]
    sols = sorted(solve(conds, b0, pidx, store), key=binding_key) if b0 is not None else []
    if not sols:
        return None
    b = sols[0]
    return {"clause": f"{lit.pred}#{clause.index}", "where": str(clause.loc or ""),
            "kind": "holds", "bindings": _plain(b), "solutions": len(sols),
            "conditions": [{"condition": str(c), "as": show(c, b),
                            "matched": _matched(c, b, pidx)} for c in conds]}


def why(program: Program, lit: Literal, percepts: list, model: list) -> dict[str, Any]:
    """The report on ``lit`` (a concept instance) for one cycle's ``percepts`` (neutral lists)
    and world ``model`` (asserted facts): believed, and each clause matched."""
    pidx = PerceptIndex(as_percepts(percepts))
    store = store_of(Engine(program).infer(pidx, model))
    believed = next(solve([Literal(lit.pred, lit.args)], {}, pidx, store), None) is not None
    asserted = any(row and row[0] == lit.pred and len(row) == len(lit.args) + 1 and unify_head(
        lit, Literal(lit.pred, tuple(row[1:]))) is not None for row in map(list, model))
    failing = {c["clause"]: c for c in why_false(program, lit, pidx, store)}
    clauses = []
    for clause in program.concepts.get(lit.pred, ()):
        name = f"{lit.pred}#{clause.index}"
        found = _holds(clause, lit, pidx, store) or failing.get(name) or {
            "clause": name, "where": str(clause.loc or ""), "kind": "head",
            "cond": f"its head {clause.head} does not match {lit}"}
        clauses.append(found)
    return {"instance": str(lit), "believed": believed, "asserted": asserted,
            "clauses": clauses}


def _failure_lines(c: dict[str, Any], indent: str) -> list[str]:
    """What made one clause fail (a derivations.why_false entry), as text lines."""
    every = " (for every binding of the conditions before it)" if c.get("every") else ""
    lines = [f"{indent}clause {c['clause']} ({c['where']}) fails at {c['cond']}{every}"]
    more = indent + "  "
    if c["kind"] == "unseen":
        lines += [f"{more}percept seen instead: {p}" for p in c["seen"]] or \
            [f"{more}no percept of that object"]
    elif c["kind"] == "test":
        values = ", ".join(f"?{k} = {v}" for k, v in c["values"].items())
        lines.append(f"{more}with {values or 'its variables unbound'}")
    elif c["kind"] == "negated":
        for b in c["because"]:
            by = f" (by {b['clause']}: {' '.join(b['percepts'] + b['relations'])})" \
                if b["clause"] else ""
            lines.append(f"{more}but believed: {b['belief']}{by}")
        if c.get("more"):
            lines.append(f"{more}and {c['more']} more")
    elif c["kind"] == "missing":
        lines.append(f"{more}no such belief" + (", because:" if c["below"] else ""))
        for below in c["below"]:
            lines += _failure_lines(below, more + "  ")
    elif c["kind"] == "holds":
        lines[0] = f"{indent}clause {c['clause']} ({c['where']}): {c.get('note', '')}"
    return lines


def why_text(report: dict[str, Any], where: str) -> str:
    """The report for a person (``where``: "at cycle N of run R (agent A)")."""
    verdict = "believed" if report["believed"] else "not believed"
    lines = [f"{report['instance']} {where}: {verdict}"]
    if report["asserted"]:
        lines.append("  asserted in the agent's world model (a fact an SCS body asserted)")
    if not report["clauses"] and not report["asserted"]:
        lines.append("  no clause defines it (a predicate only SCS bodies assert)")
    for c in report["clauses"]:
        if c["kind"] == "head":
            lines.append(f"  clause {c['clause']} ({c['where']}): {c['cond']}")
        elif c["kind"] == "holds" and "conditions" in c:
            binds = ", ".join(f"{k}={v}" for k, v in c["bindings"].items())
            more = f"; {c['solutions']} bindings, the first shown" if c["solutions"] > 1 else ""
            lines.append(f"  clause {c['clause']} ({c['where']}) holds with "
                         f"{binds or 'no bindings'}{more}:")
            width = max((len(x["as"]) for x in c["conditions"]), default=0)
            lines += [f"    {x['as']:<{width}}  <- {x['matched']}" for x in c["conditions"]]
        else:
            lines += _failure_lines(c, "  ")
    return "\n".join(lines)
