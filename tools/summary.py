"""The end-of-run summary of `teleo launch`, built from the files the processes leave in the
run folder (world/recorder.py): the trace (cycles run, last counters), the world's health
record (agents left uncontrolled, late, dead and stalled stages, world restarts), the world's
final totals when it wrote them, the goal store, and the launcher's own record (restarts per
process, processes left down, why the run ended). The files are read as they are, so the
figures stay true when the world was killed.

The run's status (docs/faults.md, "What counts as a failed run"):
- failed (exit 1): an agent was uncontrolled for at least one cycle (its actions did not
  arrive and the world applied its safe action), a process gave up (left down after its
  restarts, or a world that could not resume), a goal could not be kept (the executive
  reported it failed), or the world stopped before its cycles were done for any other reason
  than a stop asked for. A goal still at an impasse at the end (no skill path yet; the
  problem solver may have been working on it) is listed as not achieved, not as failed;
- interrupted (exit 130): stopped on request (Ctrl-C, `teleo stop`) before its cycles were
  done, with nothing failed; a run without a cycle limit ends this way and counts as completed;
- completed (exit 0): otherwise. Stalls, late stages and restarts that recovered are shown
  but do not fail a run.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import click

from world.recorder import HEALTH, SNAPSHOTS, TRACE, WORLD_FINAL, read_jsonl

GOALS_FILE = "goals.json"
EXIT_CODES = {"completed": 0, "failed": 1, "interrupted": 130}
_NOT_KEPT = ("failed",)
__all__ = ["GOALS_FILE", "SNAPSHOTS", "build", "echo", "exit_code", "render"]


def build(run_dir: Path, base: dict[str, Any], restarts: dict[str, int],
          domain: str = "driving", left_down: tuple[str, ...] = (), ended: str = "",
          requested_stop: bool = False) -> dict[str, Any]:
    """The summary as a JSON-able dict. `base` holds run, scenario, mode, seed, requested
    cycles; `left_down`: processes the launcher gave up on; `ended`: the launcher's reason
    for ending the run early; `requested_stop`: a user asked for the stop."""
    from world.domain import get_domain

    spec = get_domain(domain)
    trace = read_jsonl(run_dir / TRACE)
    health = read_jsonl(run_dir / HEALTH)
    final = _read_json(run_dir / WORLD_FINAL) or {}
    cycles = len(trace)
    counters: dict[str, dict[str, int]] = trace[-1].get("counters", {}) if trace else {}
    elapsed = _elapsed(health)
    raw = (_read_json(run_dir / GOALS_FILE) or {}).get("goals")
    goals = [g for g in raw if isinstance(g, dict)] if isinstance(raw, list) else []
    totals = _totals(health)
    summary = {
        **base,
        "cycles": cycles,
        "elapsed_s": round(elapsed, 3),
        "cycles_per_s": round(cycles / elapsed, 2) if elapsed > 0 else 0.0,
        "uncontrolled": totals["noop"],
        "late_stages": totals["late"],
        "dead_stages": totals["dead"],
        "stalls": _stalls(health),
        "restarts": {name: n for name, n in restarts.items() if n},
        "world_resumes": [{k: h.get(k) for k in ("cycle", "checkpoint", "replayed")}
                          for h in health if h.get("kind") == "start" and h.get("resumed")],
        "left_down": list(left_down),
        "goals": goals,
        "goals_achieved": sum(1 for g in goals if g.get("status") == "achieved"),
        "domain": domain,
        "achievements": {a: {k: int(c.get(k, 0)) for k in spec.achievements}
                         for a, c in counters.items()},
        "law_violations": {a: {k: int(c.get(k, 0)) for k in spec.violations}
                           for a, c in counters.items()},
        "counters": counters,
        "trace": str(run_dir / TRACE),
        "world_reason": final.get("reason", "the world did not finish (killed)"),
    }
    summary["failures"] = _failures(summary, ended)
    summary["status"] = _status(summary, requested_stop)
    summary["completed"] = summary["status"] == "completed"
    return summary


def _totals(health: list[dict[str, Any]]) -> dict[str, dict[str, int]]:
    totals: dict[str, dict[str, int]] = {k: {} for k in ("noop", "late", "dead")}
    for h in health:
        if h.get("kind") != "cycle":
            continue
        for k, counter in totals.items():
            for name in h.get(k, ()):
                counter[name] = counter.get(name, 0) + 1
    return totals


def _stalls(health: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Cycles that waited past the stall threshold: when, how long [s], for whom."""
    return [{"cycle": h["cycle"], "seconds": h.get("elapsed_s", 0.0), "stages": h["stalled"]}
            for h in health if h.get("kind") == "cycle" and h.get("stalled")]


def _elapsed(health: list[dict[str, Any]]) -> float:
    """From the first cycle (all processes ready) to the world's last line [s]; restarts
    and downtime included."""
    times = [float(h["t"]) for h in health if isinstance(h.get("t"), int | float)]
    ready = [float(h["t"]) for h in health if h.get("kind") == "ready" and "t" in h]
    return max(times) - (ready[0] if ready else min(times)) if times else 0.0


def _failures(s: dict[str, Any], ended: str) -> list[str]:
    out = [f"{agent} uncontrolled for {n} cycle(s) (the world applied its safe action)"
           for agent, n in s["uncontrolled"].items()]
    out += [f"{name} gave up (left down after {s['restarts'].get(name, 0)} restart(s))"
            for name in s["left_down"]]
    out += [f"goal {g.get('id')} {g.get('goal')} could not be kept: {g.get('status')}"
            + (f" ({g['note']})" if g.get("note") else "")
            for g in s["goals"] if g.get("status") in _NOT_KEPT]
    if ended:
        out.append(ended)
    return out


def _status(s: dict[str, Any], requested_stop: bool) -> str:
    if s["failures"]:
        return "failed"
    wanted = int(s.get("cycles_requested") or 0)
    if wanted and s["cycles"] < wanted:
        if requested_stop:
            return "interrupted"
        s["failures"].append(f"the world stopped at cycle {s['cycles']} of {wanted}: "
                             f"{s['world_reason']}")
        return "failed"
    return "completed"


def exit_code(summary: dict[str, Any]) -> int:
    """0 completed, 1 failed, 130 interrupted (module doc)."""
    return EXIT_CODES[summary["status"]]


def echo(summary: dict[str, Any]) -> None:
    """Print the summary for a person."""
    state = {"completed": "completed", "failed": "FAILED", "interrupted": "INTERRUPTED"}
    click.echo(f"run {summary['run']} {state[summary['status']]}: {summary['cycles']} cycles "
               f"in {summary['elapsed_s']} s ({summary['cycles_per_s']} cycles/s, "
               f"{summary['mode']}, seed {summary['seed']})")
    for reason in summary["failures"]:
        click.echo(f"  failed: {reason}")
    late, dead = summary["late_stages"], summary["dead_stages"]
    click.echo(f"  late stages: {sum(late.values())}{_pairs(late)}")
    if dead:
        click.echo(f"  dead stages: {sum(dead.values())} cycle(s){_pairs(dead)}")
    stalls = summary["stalls"]
    if stalls:
        shown = ", ".join(f"{'+'.join(s['stages'])} {s['seconds']} s at cycle {s['cycle']}"
                          for s in stalls[:5])
        click.echo(f"  stalls: {len(stalls)} ({shown}{', ...' if len(stalls) > 5 else ''})")
    click.echo(f"  restarts: {sum(summary['restarts'].values())}{_pairs(summary['restarts'])}")
    for r in summary["world_resumes"]:
        click.echo(f"    world resumed at cycle {r['cycle']} (checkpoint {r['checkpoint']}, "
                   f"{r['replayed']} cycles replayed)")
    click.echo(f"  goals achieved: {summary['goals_achieved']} of {len(summary['goals'])}")
    for goal in summary["goals"]:
        click.echo(f"    {goal.get('id')} {goal.get('agent')} {goal.get('goal')} "
                   f"p{goal.get('priority')}: {goal.get('status')}")
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

    snaps = read_jsonl(run_dir / SNAPSHOTS)
    if not snaps:
        return 0
    out.parent.mkdir(parents=True, exist_ok=True)
    return domain_of(snaps[0]).render(snaps, out, agent)


def _read_json(path: Path) -> dict[str, Any] | None:
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    return doc if isinstance(doc, dict) else None
