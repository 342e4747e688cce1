"""The end-of-run summary of `teleo launch`, built from the files the processes leave in the
run folder (world/recorder.py): the trace (cycles run, last counters), the world's health
record (agents left uncontrolled, late, dead and stalled stages, world restarts), the world's
final totals when it wrote them, the goal store, and the launcher's own record (restarts per
process, processes left down, why the run ended). The files are read as they are, so the
figures stay true when the world was killed. What each agent's mechanisms did (learned
skills, SCS bodies, the ROGUE planner) is told by tools/records/summary_agents.py.

The run's status (completed, failed, interrupted) is decided by tools/records/run_status.py.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from tools.records import goal_reports
from tools.records import run_record as records
from tools.records.record_coverage import coverage
from tools.records.run_status import finish_status
from tools.records.summary_agents import (
    agent_sections,
    natural,
    read_json_file,
    set_aside,
)
from tools.records.summary_text import echo
from world.recorder import HEALTH, SNAPSHOTS, TRACE, WORLD_FINAL, complete_lines_bytes, read_jsonl

log = logging.getLogger(__name__)
GOALS_FILE = "goals.json"
__all__ = ["GOALS_FILE", "SNAPSHOTS", "build", "echo", "learned_file", "render", "state_file"]


def learned_file(run_dir: Path, agent: str) -> Path:
    """Where the executive of ``agent`` writes its learned skills (program syntax)."""
    return run_dir / f"learned-{agent}.tlp"


def swapped_file(run_dir: Path, agent: str) -> Path:
    """Where the inference and executive of ``agent`` keep a program swapped in while the run
    runs (`teleo program load`), so that a restart runs it (agents/processes/swapping.py)."""
    return run_dir / f"program-{agent}.json"


def state_file(run_dir: Path, agent: str) -> Path:
    """Where the executive of ``agent`` keeps its engine state across a restart."""
    return run_dir / f"state-{agent}.json"


def build(run_dir: Path, base: dict[str, Any], restarts: dict[str, int],
          domain: str = "driving", left_down: tuple[str, ...] = (), ended: str = "",
          requested_stop: bool = False, scripted: Sequence[Any] = (),
          recorder: dict[str, Any] | None = None) -> dict[str, Any]:
    """The summary as a JSON-able dict. `base` holds run, scenario, mode, seed, requested
    cycles; `left_down`: processes the launcher gave up on; `ended`: the launcher's reason
    for ending the run early; `requested_stop`: a user asked for the stop; `scripted`: the
    scenario's events (ScriptedEvent: at_cycle, event); `recorder`: the launch recorder's
    report (tools/records/recorder.py BusRecorder.report: a write that failed, a drain cut
    short)."""
    from world.domain import get_domain

    spec = get_domain(domain)
    cycles, last, trace = _trace(run_dir / TRACE)
    health = read_jsonl(run_dir / HEALTH)
    final = read_json_file(run_dir / WORLD_FINAL)
    final = final if isinstance(final, dict) else {}
    counters: dict[str, dict[str, int]] = last.get("counters", {})
    elapsed = _elapsed(health)
    goals, incidents, refused = _goals(run_dir / GOALS_FILE)
    record = _open_record(run_dir)
    goals = goal_reports.with_history(goals, run_dir, record)  # when each became active, ...
    totals = _totals(health)
    memory: dict[str, Any] = {}
    for line in trace:  # each change of an agent's memory, in order
        memory.update(line.get("memory", {}))
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
        "goal_store_incidents": incidents,
        "requests_refused": refused,
        "goals_lost": any(i.startswith("GOALS LOST") for i in incidents),
        "domain": domain,
        "achievements": {a: {k: int(c.get(k, 0)) for k in spec.achievements}
                         for a, c in counters.items()},
        "law_violations": {a: {k: int(c.get(k, 0)) for k in spec.violations}
                           for a, c in counters.items()},
        "counters": counters,
        **agent_sections(run_dir, counters, memory),
        **set_aside(run_dir),
        "trace": str(run_dir / TRACE),
        **_record(run_dir, cycles, record, recorder or {}),
        "world_reason": final.get("reason", "the world did not finish (killed)"),
        "cycle_time": cycle_time(final.get("timing_ms"), cycles),
        "events_refused": refused_events(trace, scripted),
        **({"episode": final["episode"]} if "episode" in final else {}),  # gymnasium's
    }
    return finish_status(summary, ended, requested_stop)


def _trace(path: Path) -> tuple[int, dict[str, Any], list[dict[str, Any]]]:
    """(cycles run, the last cycle's line, the lines with events or memory changes) of a
    trace: only those lines are parsed, so a run of 74,000 cycles is summarised in a tenth
    of the time that parsing each line took (the stop of a long run waits for it)."""
    lines = complete_lines_bytes(path)
    notable = [json.loads(x) for x in lines if b'"events"' in x or b'"memory"' in x]
    last = json.loads(lines[-1]) if lines else {}
    return len(lines), last if isinstance(last, dict) else {}, \
        [x for x in notable if isinstance(x, dict)]


def refused_events(trace: Iterable[dict[str, Any]], scripted: Sequence[Any]
                   ) -> list[dict[str, Any]]:
    """The scenario's own events that the world refused, [{"cycle", "event", "reason"}]
    (one a user sent with `teleo event` had its verdict then): the run did not go as
    written."""
    due = {(ev.at_cycle, json.dumps(ev.event, sort_keys=True)) for ev in scripted}
    return [{"cycle": line["cycle"], "event": e.get("event"), "reason": e.get("reason", "")}
            for line in trace for e in line.get("events", ())
            if e.get("status") == "failed"
            and (line.get("cycle"), json.dumps(e.get("event"), sort_keys=True)) in due]


def cycle_time(timing: Any, cycles: int) -> dict[str, Any]:
    """The mean lockstep cycle [ms] and each process's share of it [%] (its compute time;
    the rest is the bus, zenoh and msgpack, and waiting), from the world's timing totals;
    {} when the world did not write them (killed) or no cycle ran."""
    if not isinstance(timing, dict) or cycles <= 0:
        return {}
    cycle_ms = (float(timing.get("cycle", 0.0)) + float(timing.get("world", 0.0))) / cycles
    if cycle_ms <= 0:
        return {}
    means = {"world": float(timing.get("world", 0.0)) / cycles}
    order = {"goals": 0, "perception": 1, "inference": 2, "executive": 3}
    stages = sorted((timing.get("stages") or {}).items(),
                    key=lambda kv: (order.get(kv[0].rpartition(".")[2], 4), natural(kv[0])))
    means.update({name: float(ms) / cycles for name, ms in stages})
    shares = {name: round(100 * ms / cycle_ms, 1) for name, ms in means.items()}
    shares["bus and waits"] = round(max(0.0, 100 - sum(shares.values())), 1)
    return {"ms": round(cycle_ms, 3), "shares": shares}


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
    return [{"cycle": h["cycle"], "seconds": h.get("elapsed_s", h.get("seconds", 0.0)),
             "stages": h["stalled"], **({"at_stop": True} if h.get("at_stop") else {})}
            for h in health if h.get("kind") in ("cycle", "stalled") and h.get("stalled")]


def _elapsed(health: list[dict[str, Any]]) -> float:
    """From the first cycle (all processes ready) to the world's last line [s]; restarts
    and downtime included."""
    times = [float(h["t"]) for h in health if isinstance(h.get("t"), int | float)]
    ready = [float(h["t"]) for h in health if h.get("kind") == "ready" and "t" in h]
    return max(times) - (ready[0] if ready else min(times)) if times else 0.0


def _open_record(run_dir: Path) -> records.RunRecord | None:
    """The run's record, read once for its goal histories and its coverage (None: none)."""
    path = run_dir / records.RECORD_FILE
    try:
        return records.RunRecord(path) if path.is_file() else None
    except records.RecordError as exc:
        log.warning("run record not read: %s", exc)
        return None


def _record(run_dir: Path, cycles: int, record: records.RunRecord | None,
            recorder: dict[str, Any]) -> dict[str, Any]:
    """"record": the run record's path (None: not recorded), as simulate's summary has it;
    "record_missing": how many cycles' world states it lacks, "record_gaps": which
    ([[first, last], ...]; both None when it cannot be read); "record_failed": the write
    that failed ({"cycle", "reason"}: nothing recorded from about that cycle), or None."""
    kept = coverage(run_dir, cycles, record)
    return {"record": kept and kept["file"], "record_missing": kept and kept["missing"],
            "record_gaps": kept and kept["gaps"],
            "record_failed": recorder.get("failed") or None,
            "record_cut_short": bool(recorder.get("cut_short"))}


def render(run_dir: Path, out: Path, agent: str) -> int:
    """Draw the run to `out`: a GIF of the saved snapshots, or a PNG of the last one with the
    agent's path over the whole run. Returns the number of frames used (0 when none saved)."""
    from world.domain import domain_of

    snaps = read_jsonl(run_dir / SNAPSHOTS)
    if not snaps:
        return 0
    out.parent.mkdir(parents=True, exist_ok=True)
    return domain_of(snaps[0]).render(snaps, out, agent)


def _goals(path: Path) -> tuple[list[dict[str, Any]], list[str], list[str]]:
    """The goal records, recovery incidents and refused scripted requests of the goal store,
    whatever shape the file has: only records that are objects are kept; a file that is not
    a goal store adds an incident saying so (a goal that is an integer must not crash the
    summary)."""
    doc = read_json_file(path)
    if doc is None:
        return [], ([f"{path}: not readable as JSON"] if path.exists() else []), []
    goals = doc.get("goals", []) if isinstance(doc, dict) else None
    if not isinstance(goals, list):
        return [], [f"{path}: not a goal store (no list of goals)"], []
    keep = [g for g in goals if isinstance(g, dict)]
    incidents = [str(i) for i in doc.get("incidents", [])] \
        if isinstance(doc.get("incidents"), list) else []
    if len(keep) != len(goals):
        incidents.append(f"{path}: {len(goals) - len(keep)} goal record(s) are not objects")
    refused = doc.get("refused")
    return keep, incidents, [str(r) for r in refused] if isinstance(refused, list) else []
