"""The end-of-run summary of `teleo launch`, built from the files the processes leave in the
run folder: the world's final counters (`world-final.json`), the goal store (`goals.json`),
the snapshots for rendering (`snapshots.jsonl`) and the launcher's restart counts.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import click

WORLD_FINAL = "world-final.json"
GOALS_FILE = "goals.json"
SNAPSHOTS = "snapshots.jsonl"
TRACE = "trace.jsonl"


def build(run_dir: Path, base: dict[str, Any], restarts: dict[str, int],
          domain: str = "driving") -> dict[str, Any]:
    """The summary as a JSON-able dict. `base` holds run, scenario, mode, seed, requested
    cycles; missing files (a crashed world) give zeros and `completed: false`. The domain
    says which counters are violations and which are work done (world/domain.py)."""
    from world.domain import get_domain

    spec = get_domain(domain)
    final = _read_json(run_dir / WORLD_FINAL) or {}
    goals = (_read_json(run_dir / GOALS_FILE) or {}).get("goals", [])
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
        "domain": domain,
        "achievements": {a: {k: int(c.get(k, 0)) for k in spec.achievements}
                         for a, c in counters.items()},
        "law_violations": {a: {k: int(c.get(k, 0)) for k in spec.violations}
                           for a, c in counters.items()},
        "counters": counters,
        "trace": str(run_dir / TRACE),
    }


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
    for goal in summary["goals"]:
        click.echo(f"    {goal['id']} {goal['agent']} {goal['goal']} p{goal['priority']}: "
                   f"{goal['status']}")
    for agent, laws in summary["law_violations"].items():
        done = summary["achievements"].get(agent, {})
        work = "".join(f"{k} {v}, " for k, v in done.items())
        click.echo(f"  {agent}: {work}law violations {sum(laws.values())}{_pairs(laws)}")


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


def _read_json(path: Path) -> dict[str, Any] | None:
    try:
        return json.loads(path.read_text())
    except (FileNotFoundError, ValueError):
        return None
