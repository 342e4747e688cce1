"""`teleo record info RECORD [--json]`: what a run record holds, as `ros2 bag info` says of a
bag: its run, cycles, duration, agents, every channel (bus key) with its message kinds and
count, and each goal's final status (docs/records.md, "What a record holds").

RECORD is a record file, a run folder or a run id (tools/records/run_record.py, `locate`);
a record whose writer was killed is read as far as it goes, and says so. `teleo record
FILE.mcap` records; `info` as its first argument asks this command instead
(RecordWithInfo, the class of `teleo record`).
"""

from __future__ import annotations

import json
from collections import Counter, defaultdict
from typing import Any

import click


def summarise(path_or_run: str) -> dict[str, Any]:
    """The summary of the record of `path_or_run` as plain data; raises RecordError."""
    from tools.records.run_record import RunRecord, locate

    path = locate(path_or_run)
    record = RunRecord(path)
    counts: Counter[str] = Counter()
    kinds: dict[str, set[str]] = defaultdict(set)
    sent: list[int] = []
    times: list[float] = []
    cycles: set[int] = set()
    for key, rec in record.records():
        counts[key] += 1
        kinds[key].add(str(rec.get("kind", "?")))
        env = rec.get("env") or {}
        if isinstance(env.get("sent_ns"), int):
            sent.append(env["sent_ns"])
        if isinstance(env.get("cycle"), int) and env["cycle"] >= 0:
            cycles.add(env["cycle"])
        if rec.get("kind") == "WorldState":
            t = (rec.get("snapshot") or {}).get("time")
            if isinstance(t, int | float):
                times.append(float(t))
    meta = record.meta.get("teleo.run", {})
    return {
        "file": str(path), "bytes": path.stat().st_size, "run": record.run,
        "source": meta.get("source", ""), "scenario": meta.get("scenario", ""),
        "domain": meta.get("domain", ""), "truncated": record.truncated,
        "cycles": {"first": min(cycles) if cycles else None,
                   "last": max(cycles) if cycles else None,
                   "states_held": record.held_ranges()},
        "world_s": round(max(times) - min(times), 3) if times else 0.0,
        "wall_s": round((max(sent) - min(sent)) / 1e9, 3) if sent else 0.0,
        "agents": record.agents(),
        "messages": sum(counts.values()),
        "channels": [{"key": k, "kinds": sorted(kinds[k]), "count": counts[k]}
                     for k in sorted(counts)],
        "goals": {agent: [_final(gid, changes) for gid, changes in goals.items()]
                  for agent, goals in sorted(record.goal_history().items())},
    }


def _final(goal_id: str, changes: list[dict[str, Any]]) -> dict[str, Any]:
    """A goal's last recorded change: its final status, and the cycle it took it."""
    last = changes[-1] if changes else {}
    return {"id": goal_id, "goal": last.get("goal", ""), "status": last.get("status", ""),
            "cycle": last.get("cycle"), "priority": last.get("priority"),
            "note": last.get("note", "")}


def _text(s: dict[str, Any]) -> str:
    c = s["cycles"]
    span = "none" if c["first"] is None else f"{c['first']}-{c['last']}"
    held = ", ".join(f"{a}-{b}" if a != b else str(a) for a, b in c["states_held"]) or "none"
    where = ", ".join(f"{k} {s[k]}" for k in ("source", "domain", "scenario") if s[k])
    lines = [f"record:   {s['file']} ({s['bytes'] / 1024:.1f} KiB)"
             + ("; never closed: read as far as it goes" if s["truncated"] else ""),
             f"run:      {s['run']}" + (f" ({where})" if where else ""),
             f"cycles:   {span} (world states held: {held})",
             f"duration: {s['world_s']:g} s world time, {s['wall_s']:g} s wall clock",
             f"agents:   {', '.join(s['agents']) or 'none'}",
             f"messages: {s['messages']} on {len(s['channels'])} channels"]
    width = max((len(str(ch["count"])) for ch in s["channels"]), default=1)
    lines += [f"  {ch['count']:>{width}}  {'/'.join(ch['kinds']):<14} {ch['key']}"
              for ch in s["channels"]]
    goals = [(a, g) for a, gs in s["goals"].items() for g in gs]
    lines.append(f"goals:    {len(goals) or 'none'}")
    for agent, g in goals:
        note = f" ({g['note']})" if g["note"] else ""
        lines.append(f"  {agent} {g['id']} {g['goal']}: {g['status']} at cycle {g['cycle']}"
                     f"{note}")
    return "\n".join(lines)


@click.command("info")
@click.argument("record")
@click.option("--json", "as_json", is_flag=True,
              help='One JSON object: {"file", "run", "cycles", "world_s", "wall_s", "agents", '
                   '"messages", "channels", "goals", ...}.')
def info(record: str, as_json: bool) -> None:
    """Summarise a run record: run, cycles, duration, agents, channels, goals.

    RECORD is a record (.mcap), a run folder or a run id (as `teleo explain`), as `ros2
    bag info`."""
    from tools.records.run_record import RecordError

    try:
        summary = summarise(record)
    except RecordError as exc:
        raise click.ClickException(f"record info: {exc}") from None
    click.echo(json.dumps(summary) if as_json else _text(summary))


class RecordWithInfo(click.Command):
    """`teleo record`: `teleo record info RECORD` is the summary (`info`), anything else
    records (a FILE ends in .mcap, so no record file is named `info`)."""

    def make_context(self, info_name: str | None, args: list[str],
                     parent: click.Context | None = None, **extra: Any) -> click.Context:
        if args[:1] == ["info"]:
            return info.make_context(f"{info_name} info", args[1:], parent=parent, **extra)
        return super().make_context(info_name, args, parent=parent, **extra)


commands: list[click.Command] = []  # reached as `teleo record info` (tools/commands/bus.py)
