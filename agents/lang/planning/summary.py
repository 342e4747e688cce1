"""ROGUE's part of the run summary (seed 003): from the agent's saved planner state, the
operators it executed (its head-plan) with what monitoring found, each request's end, the
choices its failed steps excluded (failure memory), the distance travelled (odometer) and,
by the map, that of the executed order and of first-come-first-served."""

from __future__ import annotations

from typing import Any

from ..core.mechanism import AgentRecord


def planner_entry(agent: AgentRecord) -> dict[str, Any] | None:
    """The agent's "planner" entry, or None for an agent the planner did not run."""
    planner = agent.state.get("planner") or {}
    if not planner:
        return None
    travel = planner.get("travel", {})
    return {
        "executed": [{"step": a["step"], "tasks": a["tasks"], "result": a["result"],
                      "note": a.get("note", ""), "ended": a["ended"]}
                     for a in planner.get("head", ())],
        "requests": [{"id": f["goal_id"], "goal": f["goal"], "status": f["status"],
                      "reason": f.get("reason", ""), "arrived": f["arrived"],
                      "ended": f["ended"]} for f in planner.get("finished", ())],
        "pending": [t["goal_id"] for t in planner.get("tasks", ())],
        "excluded": [{"id": r["goal_id"], **x} for r in (*planner.get("finished", ()),
                                                        *planner.get("tasks", ()))
                     for x in r.get("excluded", ())],
        "travelled_m": round(agent.counters.get("travel_cm", 0) / 100, 2),
        "executed_m": travel.get("executed_m", 0.0), "fcfs_m": travel.get("fcfs_m", 0.0),
        "log": planner.get("log", [])}


def planner_lines(name: str, plan: dict[str, Any]) -> list[str]:
    """The entry as the summary prints it."""
    out = [f"  {name}: operators executed (ROGUE head-plan): {len(plan['executed'])}"]
    for a in plan["executed"]:
        extra = "" if a["result"] in ("verified", "applied") else f" ({a['note']})"
        out.append(f"    {a['step']} for {' '.join(a['tasks'])}: {a['result']}{extra}")
    if plan.get("excluded"):
        out.append(f"  {name}: choices excluded by failed steps (failure memory): "
                   f"{len(plan['excluded'])}")
    for x in plan.get("excluded", ()):
        held = " ".join(x["depends"]) or f"(not {x['achieves']})"
        out.append(f"    {x['id']} {x['step']} for {x['achieves']} at cycle {x['since']}: "
                   f"{x['why']}; " + (f"open again at cycle {x['opened']}: {x['reopened']}"
                                      if x["opened"] >= 0 else f"stands while {held} holds"))
    out.append(f"  {name}: travelled {plan['travelled_m']:.1f} m (odometer); by the map "
               f"{plan['executed_m']:.1f} m in the executed order, "
               f"{plan['fcfs_m']:.1f} m first-come-first-served")
    return out
