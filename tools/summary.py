"""The end-of-run summary of `teleo launch`, built from the files the processes leave in the
run folder: the world's final counters and each agent's last memory (`world-final.json`), the
goal store (`goals.json`), the snapshots for rendering (`snapshots.jsonl`), each agent's
learned skills (`learned-AGENT.tlp`), the planner's head-plan and travel figures in each
executive's state file (`state-AGENT.json`) and the launcher's restart counts.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import click

from tools import records

WORLD_FINAL = "world-final.json"
GOALS_FILE = "goals.json"
SNAPSHOTS = "snapshots.jsonl"
TRACE = "trace.jsonl"


def learned_file(run_dir: Path, agent: str) -> Path:
    """Where the executive of ``agent`` writes its learned skills (program syntax)."""
    return run_dir / f"learned-{agent}.tlp"


def state_file(run_dir: Path, agent: str) -> Path:
    """Where the executive of ``agent`` keeps its engine state across a restart."""
    return run_dir / f"state-{agent}.json"


def build(run_dir: Path, base: dict[str, Any], restarts: dict[str, int],
          domain: str = "driving") -> dict[str, Any]:
    """The summary as a JSON-able dict. `base` holds run, scenario, mode, seed, requested
    cycles; missing files (a crashed world) give zeros and `completed: false`. The domain
    says which counters are violations and which are work done (world/domain.py)."""
    from world.domain import get_domain

    spec = get_domain(domain)
    final = _read_json(run_dir / WORLD_FINAL)
    final = final if isinstance(final, dict) else {}
    goals, incidents = _goals(run_dir / GOALS_FILE)
    goals = records.with_history(goals, run_dir)  # when each became active, achieved, ...
    counters: dict[str, dict[str, int]] = final.get("counters", {})
    elapsed = float(final.get("elapsed_s", 0.0))
    cycles = int(final.get("cycles", 0))
    return {
        **base,
        "completed": bool(final.get("completed", False)),
        "cycles": cycles,
        "elapsed_s": round(elapsed, 3),
        "cycles_per_s": round(cycles / elapsed, 2) if elapsed > 0 else 0.0,
        "late_stages": final.get("late", {}),
        "dead_stages": final.get("dead", {}),
        "restarts": {name: n for name, n in restarts.items() if n},
        "goals": goals,
        "goals_achieved": sum(1 for g in goals if g.get("status") == "achieved"),
        "goal_store_incidents": incidents,
        "goals_lost": any(i.startswith("GOALS LOST") for i in incidents),
        "domain": domain,
        "achievements": {a: {k: int(c.get(k, 0)) for k in spec.achievements}
                         for a, c in counters.items()},
        "law_violations": {a: {k: int(c.get(k, 0)) for k in spec.violations}
                           for a, c in counters.items()},
        "counters": counters,
        "learned": _learned(run_dir),
        "planner": _planner(run_dir, counters),
        "bodies": {a: b for a, m in sorted(final.get("memory", {}).items())
                   if (b := bodies(m))},
        "trace": str(run_dir / TRACE),
    }


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


def echo(summary: dict[str, Any]) -> None:
    """Print the summary for a person."""
    state = "completed" if summary["completed"] else "INCOMPLETE"
    click.echo(f"run {summary['run']} {state}: {summary['cycles']} cycles in "
               f"{summary['elapsed_s']} s ({summary['cycles_per_s']} cycles/s, "
               f"{summary['mode']}, seed {summary['seed']})")
    late = summary["late_stages"]
    click.echo(f"  late stages: {sum(late.values())}{_pairs(late)}")
    click.echo(f"  restarts: {sum(summary['restarts'].values())}{_pairs(summary['restarts'])}")
    click.echo(f"  goals achieved: {summary['goals_achieved']} of {len(summary['goals'])}")
    for incident in summary.get("goal_store_incidents", ()):
        click.echo(f"  GOAL STORE: {incident}")
    for goal in summary["goals"]:
        fields = [str(goal.get(k, "?")) for k in ("id", "agent", "goal", "priority", "status")]
        click.echo("    {} {} {} p{}: {}".format(*fields)
                   + records.history_text(goal.get("history", [])))
    for agent, laws in summary["law_violations"].items():
        done = summary["achievements"].get(agent, {})
        work = "".join(f"{k} {v}, " for k, v in done.items())
        click.echo(f"  {agent}: {work}law violations {sum(laws.values())}{_pairs(laws)}")
    _echo_planner(summary)
    for agent, learned in summary.get("learned", {}).items():
        heads = learned["skills"]
        click.echo(f"  {agent}: learned skills {len(heads)} ({learned['file']})"
                   + "".join(f"\n    {h}" for h in heads))
    for agent, b in summary.get("bodies", {}).items():
        _echo_bodies(agent, b)


def _planner(run_dir: Path, counters: dict[str, dict[str, int]]) -> dict[str, Any]:
    """Per agent run by the ROGUE planner (seed 003): the operators it executed (its
    head-plan) with what monitoring found, each request's end, the distance travelled
    (odometer) and, by the map, that of the executed order and of first-come-first-served."""
    out = {}
    for path in sorted(run_dir.glob("state-*.json")):
        agent = path.stem.removeprefix("state-")
        doc = _read_json(path) or {}
        planner = doc.get("state", {}).get("planner") or {}
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
        click.echo(f"  {agent}: travelled {plan['travelled_m']:.1f} m (odometer); by the map "
                   f"{plan['executed_m']:.1f} m in the executed order, "
                   f"{plan['fcfs_m']:.1f} m first-come-first-served")


def _learned(run_dir: Path) -> dict[str, dict[str, Any]]:
    """Per agent: its learned-skills file and the head of each skill in it."""
    from agents.lang.solving.learned import clause_heads

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


def _pairs(d: dict[str, Any]) -> str:
    shown = {k: v for k, v in d.items() if v}
    return " (" + ", ".join(f"{k} {v}" for k, v in shown.items()) + ")" if shown else ""


def render(run_dir: Path, out: Path, agent: str) -> int:
    """Draw the run to `out`: a GIF of the saved snapshots, or a PNG of the last one with the
    agent's path over the whole run. Returns the number of frames used (0 when none saved)."""
    from world.domain import domain_of

    path = run_dir / SNAPSHOTS
    if not path.exists():
        return 0
    snaps = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
    if not snaps:
        return 0
    out.parent.mkdir(parents=True, exist_ok=True)
    return domain_of(snaps[0]).render(snaps, out, agent)


def _goals(path: Path) -> tuple[list[dict[str, Any]], list[str]]:
    """The goal records and recovery incidents of the goal store, whatever shape the file has:
    only records that are objects are kept; a file that is not a goal store adds an incident
    saying so (drill F2: a goal that was an integer crashed the summary)."""
    doc = _read_json(path)
    if doc is None:
        return [], ([f"{path}: not readable as JSON"] if path.exists() else [])
    goals = doc.get("goals", []) if isinstance(doc, dict) else None
    if not isinstance(goals, list):
        return [], [f"{path}: not a goal store (no list of goals)"]
    keep = [g for g in goals if isinstance(g, dict)]
    incidents = [str(i) for i in doc.get("incidents", [])] \
        if isinstance(doc.get("incidents"), list) else []
    if len(keep) != len(goals):
        incidents.append(f"{path}: {len(goals) - len(keep)} goal record(s) are not objects")
    return keep, incidents


def _read_json(path: Path) -> Any:
    """The JSON in `path`, or None when it is absent or not bounded JSON (any bytes)."""
    from agents.lang import LangError
    from agents.lang.limits import read_json

    try:
        text = path.read_bytes().decode("utf-8", errors="replace")
        return read_json(text, str(path), max_chars=64 << 20, max_string=1 << 20)
    except (OSError, LangError):
        return None
