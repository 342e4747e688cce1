"""The end-of-run summary as a person reads it (`teleo launch` and `teleo simulate` print it):
the run's verdict, its failures, stages, timing, goals with their histories and each agent's
work (tools/records/summary.py builds the summary)."""

from __future__ import annotations

import textwrap
from typing import Any

import click

from tools.records import goal_reports
from tools.records.record_coverage import ranges_text
from tools.records.summary_agents import (
    SHARES_SHOWN,
    echo_agents,
    fold_lines,
    natural,
    shares_text,
    summary_agents,
)


def echo(summary: dict[str, Any]) -> None:
    """Print the summary for a person."""
    state = {"completed": "completed", "failed": "FAILED", "interrupted": "INTERRUPTED"}
    click.echo(f"run {summary['run']} {state[summary['status']]}: {summary['cycles']} cycles "
               f"in {summary['elapsed_s']} s ({summary['cycles_per_s']} cycles/s, "
               f"{summary['mode']}, seed {summary['seed']})")
    if summary.get("overrides"):
        click.echo(f"  --set: {', '.join(summary['overrides'])}")
    for reason in summary["failures"]:
        click.echo(f"  failed: {reason}")
    for reason in summary.get("goals_not_kept", ()):
        if reason not in summary["failures"]:   # [run] status = "system"
            click.echo(f"  not kept (not a failure of the run, status = system): {reason}")
    for request in summary.get("requests_refused", ()):
        click.echo(f"  {request}")
    late, dead = summary["late_stages"], summary["dead_stages"]
    click.echo(f"  late stages: {sum(late.values())}{_pairs(late)}")
    if dead:
        click.echo(f"  dead stages: {sum(dead.values())} cycle(s){_pairs(dead)}")
    stalls = summary["stalls"]
    if stalls:
        shown = ", ".join(f"{'+'.join(s['stages'])} {s['seconds']} s at cycle {s['cycle']}"
                          + (" (still stalled at the stop)" if s.get("at_stop") else "")
                          for s in stalls[:5])
        click.echo(f"  stalls: {len(stalls)} ({shown}{', ...' if len(stalls) > 5 else ''})")
    click.echo(f"  restarts: {sum(summary['restarts'].values())}{_pairs(summary['restarts'])}")
    timing = summary.get("cycle_time") or {}
    if timing:
        line = f"  cycle time {timing['ms']} ms: " + ", ".join(shares_text(timing["shares"]))
        folded = len(timing["shares"]) > 3 + 2 * SHARES_SHOWN   # many agents: wrapped too
        click.echo(textwrap.fill(line, width=100, subsequent_indent="    ",
                                 break_on_hyphens=False) if folded else line)
    for r in summary["world_resumes"]:
        click.echo(f"    world resumed at cycle {r['cycle']} (checkpoint {r['checkpoint']}, "
                   f"{r['replayed']} cycles replayed)")
    click.echo(f"  goals achieved: {summary['goals_achieved']} of {len(summary['goals'])}")
    if summary.get("episode"):   # an episodic world's (gymnasium)
        click.echo("  episode: " + ", ".join(f"{k} {v}" for k, v in summary["episode"].items()))
    for incident in summary.get("goal_store_incidents", ()):
        click.echo(f"  GOAL STORE: {incident}")
    for goal in summary["goals"]:
        fields = [str(goal.get(k, "?")) for k in ("id", "agent", "goal", "priority", "status")]
        click.echo("    {} {} {} p{}: {}".format(*fields)
                   + goal_reports.history_text(goal.get("history", [])))
    lines = []
    for agent in sorted(summary["law_violations"], key=natural):
        laws = summary["law_violations"][agent]
        done = summary["achievements"].get(agent, {})
        work = "".join(f"{k} {v}, " for k, v in done.items())
        lines.append(f"  {agent}: {work}law violations {sum(laws.values())}{_pairs(laws)}")
    for line in fold_lines(lines, summary_agents(summary)):
        click.echo(line)
    echo_agents(summary)
    if summary.get("record_missing"):
        gaps = summary.get("record_gaps") or []
        click.echo(f"  RECORD INCOMPLETE: {summary['record']} lacks the world states of "
                   f"{summary['record_missing']} of {summary['cycles']} cycles"
                   + (f" (cycles {ranges_text(gaps)})" if gaps else ""))


def _pairs(d: dict[str, Any]) -> str:
    shown = {k: v for k, v in d.items() if v}
    return " (" + ", ".join(f"{k} {v}" for k, v in shown.items()) + ")" if shown else ""
