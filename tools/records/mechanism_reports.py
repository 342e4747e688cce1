"""Each mechanism's part of the run summary: the means-ends learner's "learned" (seed 000),
SCS's "bodies" (seed 002), ROGUE's "planner" (seed 003). A Report per mechanism, kept here
with the other summaries so that the engine and its mechanisms know nothing of them; a
fourth mechanism's report is one more entry in REPORTS (or one more Report handed to
`summary_sections` and `summary_lines`)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from agents.lang.registry import clause_heads


@dataclass(frozen=True)
class AgentRecord:
    """What a run left of one agent, read by the reports: its engine state as plain data (the
    state file's "state", or EngineState.to_dict()), its last agent memory, the text of its
    learned skills (None: it kept no learned-skills file) and that file's path, and the
    world's counters for it."""

    state: Mapping[str, Any] = field(default_factory=dict)
    memory: Mapping[str, Any] = field(default_factory=dict)
    learned: str | None = None
    learned_file: str = ""
    counters: Mapping[str, int] = field(default_factory=dict)


@dataclass(frozen=True)
class Report:
    """One mechanism's entry of the run summary: its key, where its lines come among the
    reports' (lower first), its entry for one agent (None leaves the agent out) and that
    entry as the summary prints it."""

    key: str
    rank: int
    entry: Callable[[AgentRecord], dict[str, Any] | None]
    lines: Callable[[str, dict[str, Any]], list[str]]


def learned_entry(agent: AgentRecord) -> dict[str, Any] | None:
    """The agent's learned-skills file and the head of each skill in it (seed 000)."""
    if agent.learned is None:
        return None
    return {"file": agent.learned_file, "skills": clause_heads(agent.learned)}


def learned_lines(name: str, entry: dict[str, Any]) -> list[str]:
    """The entry as the summary prints it."""
    heads = entry["skills"]
    where = entry["file"] or "not saved: --learned-out FILE saves them"
    return [f"  {name}: learned skills {len(heads)} ({where})"
            + "".join(f"\n    {h}" for h in heads)]


# SCS (seed 002): what an agent's bodies did, from its last agent memory (docs/bus.md,
# "Agent memory"): the tally, each do-best alternative's record and discount factor, the
# threads still running and the world model.


def bodies_entry(agent: AgentRecord) -> dict[str, Any] | None:
    """The agent's "bodies" entry, or None for an agent without bodies."""
    memory = agent.memory
    scs = memory.get("scs") if isinstance(memory, dict) else None
    if not isinstance(scs, dict) or not (scs.get("tally") or scs.get("threads")):
        return None
    return {"tally": scs.get("tally", {}),
            "choices": scs.get("choices", []),
            "threads": [{k: t.get(k) for k in ("goal_id", "goal", "skill_name", "status", "note")}
                        for t in scs.get("threads", [])],
            "model": memory.get("model", [])}


def bodies_lines(name: str, b: dict[str, Any]) -> list[str]:
    """The entry as the summary prints it."""
    tally = ", ".join(f"{k} {v}" for k, v in sorted(b["tally"].items()))
    out = [f"  {name} SCS bodies: {tally or 'nothing done'}"]
    for c in b["choices"]:
        out.append(f"    do-best {c['label']}: chosen {c['chosen']}, succeeded "
                   f"{c['succeeded']}, failed {c['failed']}, discount factor {c['factor']:.3f}")
    for t in b["threads"]:
        out.append(f"    thread {t['goal_id']} {t['goal']} <- {t['skill_name']}: "
                   f"{t['status']} ({t['note']})")
    if b["model"]:
        out.append("    world model: " + " ".join("(" + " ".join(map(str, f)) + ")"
                                             for f in b["model"]))
    return out


# ROGUE (seed 003): from the agent's saved planner state, the operators it executed (its
# head-plan) with what monitoring found, each request's end, the choices its failed steps
# excluded (failure memory), the distance travelled (odometer) and, by the map, that of the
# executed order and of first-come-first-served.


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


REPORTS: tuple[Report, ...] = (Report("learned", 1, learned_entry, learned_lines),
                               Report("bodies", 2, bodies_entry, bodies_lines),
                               Report("planner", 0, planner_entry, planner_lines))
"""The shipped mechanisms' reports, in the order of their entries in the summary."""


def summary_sections(agents: Mapping[str, AgentRecord],
                     reports: Iterable[Report] | None = None) -> dict[str, Any]:
    """Each report's entry of the run summary, in order: per agent, by name, what the
    mechanism makes of what the run left."""
    return {r.key: {name: entry for name, agent in sorted(agents.items())
                    if (entry := r.entry(agent)) is not None}
            for r in (REPORTS if reports is None else reports)}


def summary_lines(summary: Mapping[str, Any],
                  reports: Iterable[Report] | None = None) -> list[str]:
    """The reports' entries of ``summary`` as the summary prints them."""
    out: list[str] = []
    for r in sorted(REPORTS if reports is None else reports, key=lambda r: r.rank):
        for name, entry in summary.get(r.key, {}).items():
            out += r.lines(name, entry)
    return out
