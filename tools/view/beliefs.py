"""The web view's beliefs panel: for one agent and cycle, the beliefs that make each unsatisfied
goal false (with the percept values behind them) and the beliefs its skill path depends on.

Worked out here, from the agent's program and the cycle's recorded percepts and beliefs, with
the pure engine's matcher (agents/lang, through tools/records/derivations.py, which `teleo
why` asks too), rather than carried in every decision: the record
already holds each cycle's percepts and beliefs, the explanation costs only when a page looks
at a cycle, and the Decision (so `teleo explain`, the record and the traces) stays as it is
(docs/view.md, "Why a goal is unsatisfied").

    panel = why(program, decision, percepts, beliefs)
    panel["goals"][0]["clauses"][0]["because"][0]["belief"]   # "(pedestrian-ahead ME M8)"
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from agents.lang import Belief, LangError, Percept, Program, Test, Var
from agents.lang.core.intake import PerceptIndex
from agents.lang.core.matcher import test_holds
from agents.lang.core.store import FactStore, store_of
from agents.lang.execution.paths import show
from agents.lang.reading.goals import parse_goal
from tools.records.derivations import MAX_SHOWN, matching, values, why_false, why_holds

MAX_BELIEFS = 400   # beliefs listed in the panel's "all beliefs"


def why(program: Program, decision: dict[str, Any], percepts: list, beliefs: list,
        ) -> dict[str, Any]:
    """The panel of one cycle: each unsatisfied goal's clauses with what fails in each, the
    path's skills with their :start and :requires under the path's bindings, and the beliefs
    (sorted, at most MAX_BELIEFS). Raises LangError for a percept row that is not one."""
    pidx = PerceptIndex([Percept.from_list(p) for p in percepts])
    store = store_of([Belief.from_list(b) for b in beliefs])
    goals = [_goal(program, g, pidx, store) for g in decision.get("goals", ())
             if g.get("status") != "satisfied" and g.get("instance")]
    paths = [(decision.get("goal_id", ""), decision.get("path", ()))]
    paths += [(p.get("goal_id", ""), p.get("path", ())) for p in decision.get("parallel", ())]
    steps = [{"goal_id": gid, **_step(program, s, pidx, store)} for gid, path in paths
             for s in path]
    return {"goals": goals, "path": steps, **listing(beliefs)}


def listing(beliefs: list) -> dict[str, Any]:
    """{"count", "beliefs"}: how many beliefs, and the first MAX_BELIEFS as text, sorted."""
    texts = sorted(str(Belief.from_list(b)) for b in beliefs)
    return {"count": len(texts), "beliefs": texts[:MAX_BELIEFS]}


def _goal(program: Program, goal: dict[str, Any], pidx: PerceptIndex,
          store: FactStore) -> dict[str, Any]:
    entry = {"id": goal.get("id", ""), "instance": goal["instance"],
             "status": goal.get("status", "")}
    try:
        lit = parse_goal(str(goal["instance"]), program)
    except LangError as exc:
        return {**entry, "clauses": [], "note": f"not read against the program: {exc}"}
    return {**entry, "clauses": why_false(program, lit, pidx, store)}


def _step(program: Program, step: dict[str, Any], pidx: PerceptIndex,
          store: FactStore) -> dict[str, Any]:
    """One skill of a path: its :start and :requires under the step's bindings, each with
    whether it holds on this cycle's beliefs and the belief(s) behind it."""
    entry = {"goal": step.get("goal", ""), "skill": step.get("skill", ""),
             "where": step.get("where", ""), "mode": step.get("mode", "")}
    skill = _skill(program, entry["skill"], entry["where"])
    if skill is None:
        return {**entry, "needs": [], "note": "not in the program file (a skill learned "
                                              "during the run, or the file has changed)"}
    b = {Var(k): v for k, v in step.get("bindings", {}).items()}
    needs = [{"part": part, **_need(program, c, b, pidx, store)}
             for part, conds in (("start", skill.start), ("requires", skill.requires))
             for c in conds]
    return {**entry, "needs": needs}


def _need(program: Program, cond: object, b: dict, pidx: PerceptIndex,
          store: FactStore) -> dict[str, Any]:
    if isinstance(cond, Test):
        ready = all(v in b for v in cond.variables())
        return {"cond": show(cond, b), "holds": test_holds(cond, b) if ready else None,
                "values": values(cond.variables(), b), "because": []}
    found = matching(cond, b, store)
    if not found and cond.pred not in program.concepts:
        return {"cond": show(cond, b), "holds": None, "because": [],
                "note": "not a concept: a fact the mechanism keeps (e.g. the planner's "
                        "knowledge), not among the beliefs"}
    holds = not found if cond.negated else bool(found)
    because = [why_holds(program, f, pidx, store) for f in found[:MAX_SHOWN]]
    return {"cond": show(cond, b), "holds": holds, "because": because}


def _skill(program: Program, name: str, where: str):
    """The program's skill ``name`` (pred#index), or the skill of the ROGUE operator
    ``<name args>`` (seed 003), if it is the one written at ``where``."""
    pred, _, index = name.rpartition("#")
    skills = program.skills_for(pred)
    if index.isdigit() and 0 < int(index) <= len(skills):
        skill = skills[int(index) - 1]
        return skill if _same_place(str(skill.loc or ""), where) else None
    for op in program.sections.get("operators", ()):
        if name.startswith(f"<{op.name} ") or name == f"<{op.name}>":
            if _same_place(str(op.skill.loc or op.loc), where) or _same_place(str(op.loc), where):
                return op.skill
    return None


def _same_place(a: str, b: str) -> bool:
    """Two file:line:col locations name the same place (a relative and an absolute path of
    one file agree)."""
    fa, la, ca = (a.rsplit(":", 2) + ["", ""])[:3]
    fb, lb, cb = (b.rsplit(":", 2) + ["", ""])[:3]
    if (la, ca) != (lb, cb):
        return False
    try:
        return fa == fb or Path(fa).resolve() == Path(fb).resolve()
    except (OSError, ValueError):
        return False


