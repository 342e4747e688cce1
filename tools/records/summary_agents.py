"""What each agent's mechanisms did, for the run summary (tools/records/summary.py): the skills its
problem solver learned (`learned-AGENT.tlp`), what its SCS bodies did (its last memory, as
the world's trace recorded it), and the ROGUE planner's head-plan and travel figures (its
executive's state file `state-AGENT.json`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click


def agent_sections(run_dir: Path, counters: dict[str, dict[str, int]],
                   memory: dict[str, Any]) -> dict[str, Any]:
    """The summary's "learned", "bodies" and "planner" entries."""
    planners = {path.stem.removeprefix("state-"):
                (read_json_file(path) or {}).get("state", {}).get("planner") or {}
                for path in sorted(run_dir.glob("state-*.json"))}
    return {"learned": _learned(run_dir),
            "bodies": {a: b for a, m in sorted(memory.items()) if (b := bodies(m))},
            "planner": planner_section(planners, counters)}


def echo_agents(summary: dict[str, Any]) -> None:
    """Print those entries for a person."""
    _echo_planner(summary)
    for agent, learned in summary.get("learned", {}).items():
        heads = learned["skills"]
        where = learned["file"] or "not saved: --learned-out FILE saves them"
        click.echo(f"  {agent}: learned skills {len(heads)} ({where})"
                   + "".join(f"\n    {h}" for h in heads))
    for agent, b in summary.get("bodies", {}).items():
        _echo_bodies(agent, b)


def bodies(memory: dict[str, Any]) -> dict[str, Any]:
    """What an agent's SCS bodies did, from its memory (docs/bus.md, "Agent memory"): the
    tally, each do-best alternative's record and discount factor, the threads still running
    and the world model; {} for an agent without bodies."""
    scs = memory.get("scs") if isinstance(memory, dict) else None
    if not isinstance(scs, dict) or not (scs.get("tally") or scs.get("threads")):
        return {}
    return {"tally": scs.get("tally", {}),
            "choices": scs.get("choices", []),
            "threads": [{k: t.get(k) for k in ("goal_id", "goal", "skill_name", "status", "note")}
                        for t in scs.get("threads", [])],
            "model": memory.get("model", [])}


def _learned(run_dir: Path) -> dict[str, dict[str, Any]]:
    """Per agent: its learned-skills file and the head of each skill in it."""
    from agents.lang.registry import clause_heads

    out = {}
    for path in sorted(run_dir.glob("learned-*.tlp")):
        agent = path.stem.removeprefix("learned-")
        out[agent] = {"file": str(path), "skills": clause_heads(path.read_text())}
    return out


def _echo_bodies(agent: str, b: dict[str, Any]) -> None:
    tally = ", ".join(f"{k} {v}" for k, v in sorted(b["tally"].items()))
    click.echo(f"  {agent} SCS bodies: {tally or 'nothing done'}")
    for c in b["choices"]:
        click.echo(f"    do-best {c['label']}: chosen {c['chosen']}, succeeded "
                   f"{c['succeeded']}, failed {c['failed']}, discount factor {c['factor']:.3f}")
    for t in b["threads"]:
        click.echo(f"    thread {t['goal_id']} {t['goal']} <- {t['skill_name']}: "
                   f"{t['status']} ({t['note']})")
    if b["model"]:
        click.echo("    world model: " + " ".join("(" + " ".join(map(str, f)) + ")"
                                             for f in b["model"]))


def planner_section(planners: dict[str, dict[str, Any]],
                    counters: dict[str, dict[str, int]]) -> dict[str, Any]:
    """Per agent run by the ROGUE planner (seed 003), from its saved planner state: the
    operators it executed (its head-plan) with what monitoring found, each request's end, the
    choices its failed steps excluded (failure memory), the distance travelled (odometer) and,
    by the map, that of the executed order and of first-come-first-served."""
    out = {}
    for agent, planner in sorted(planners.items()):
        if not planner:
            continue
        travel = planner.get("travel", {})
        out[agent] = {
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
            "travelled_m": round(counters.get(agent, {}).get("travel_cm", 0) / 100, 2),
            "executed_m": travel.get("executed_m", 0.0), "fcfs_m": travel.get("fcfs_m", 0.0),
            "log": planner.get("log", [])}
    return out


def _echo_planner(summary: dict[str, Any]) -> None:
    for agent, plan in summary.get("planner", {}).items():
        click.echo(f"  {agent}: operators executed (ROGUE head-plan): {len(plan['executed'])}")
        for a in plan["executed"]:
            extra = "" if a["result"] in ("verified", "applied") else f" ({a['note']})"
            click.echo(f"    {a['step']} for {' '.join(a['tasks'])}: {a['result']}{extra}")
        if plan.get("excluded"):
            click.echo(f"  {agent}: choices excluded by failed steps (failure memory): "
                       f"{len(plan['excluded'])}")
        for x in plan.get("excluded", ()):
            held = " ".join(x["depends"]) or f"(not {x['achieves']})"
            click.echo(f"    {x['id']} {x['step']} for {x['achieves']} at cycle {x['since']}: "
                       f"{x['why']}; " + (f"open again at cycle {x['opened']}: {x['reopened']}"
                                          if x["opened"] >= 0 else f"stands while {held} holds"))
        click.echo(f"  {agent}: travelled {plan['travelled_m']:.1f} m (odometer); by the map "
                   f"{plan['executed_m']:.1f} m in the executed order, "
                   f"{plan['fcfs_m']:.1f} m first-come-first-served")


def read_json_file(path: Path) -> Any:
    """The JSON in `path`, or None when it is absent or not bounded JSON (any bytes)."""
    from agents.lang import LangError
    from agents.lang.core.limits import read_json

    try:
        text = path.read_bytes().decode("utf-8", errors="replace")
        return read_json(text, str(path), max_chars=64 << 20, max_string=1 << 20)
    except (OSError, LangError):
        return None
