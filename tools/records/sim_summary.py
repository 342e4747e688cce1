"""The summary of a `teleo simulate` run in the form of `teleo launch`'s (tools/records/summary.py):
the same keys, the same goal records (ids g1, g2, ... from the goal store, statuses as the
goal-entry process reports them, each with its history of status changes, told in the loop
as the record is told them, so the summary is the same with or without a record), so a
script reads either the same way; `mode` is "simulate" and nothing is late, dead or
restarted in one process."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from tools.records import goal_reports
from tools.records.mechanism_reports import AgentRecord, summary_sections
from tools.records.run_status import episode_ended, finish_status
from tools.records.summary import refused_events
from tools.records.summary_agents import natural_sections
from world.domain import get_domain


def build(run: Any, scenario: Any, seed: int, cycles: int, trace: Path | None = None,
          learned_files: dict[str, Path] | None = None) -> dict[str, Any]:
    """The summary dict of ``run`` (a tools.commands.simulate.SimRun) of ``scenario``."""
    spec = get_domain(scenario.domain)
    counters: dict[str, dict[str, int]] = run.final.get("counters", {})
    goals = goal_reports.goals_with_history([g.to_dict() for g in run.goals.goals],
                                       dict(run.history.changes))
    done = len(run.records)
    learned_files = learned_files or {}
    summary = {
        "run": scenario.run.name, "scenario": str(scenario.path), "mode": "simulate",
        "seed": seed, "cycles_requested": cycles, "secured": False,
        "overrides": list(scenario.overrides),
        "completed": done == cycles, "cycles": done,
        "elapsed_s": round(run.elapsed_s, 3),
        "cycles_per_s": round(done / run.elapsed_s, 2) if run.elapsed_s > 0 else 0.0,
        "uncontrolled": {}, "late_stages": {}, "dead_stages": {}, "stalls": [],
        "restarts": {}, "world_resumes": [], "left_down": [],
        "goals": goals,
        "goals_achieved": sum(1 for g in goals if g["status"] == "achieved"),
        "goal_store_incidents": [], "goals_lost": False,
        "requests_refused": list(run.goals.refused), "status_policy": scenario.run.status,
        "domain": scenario.domain,
        "achievements": {a: {k: int(c.get(k, 0)) for k in spec.achievements}
                         for a, c in counters.items()},
        "law_violations": {a: {k: int(c.get(k, 0)) for k in spec.violations}
                           for a, c in counters.items()},
        "counters": counters,
        **natural_sections(summary_sections(_agents(run, scenario, counters, learned_files))),
        "trace": str(trace) if trace else "",
        "world_reason": "the episode is over" if episode_ended(run.final) else "done",
        "set_aside": [], "record_cut_short": False,   # no restart, no drain to cut
        "cycle_time": {},   # one process, no bus: no stage shares
        "events_refused": refused_events(
            (json.loads(line) for line in run.trace if '"events"' in line), scenario.events),
        **({"episode": run.final["episode"]} if "episode" in run.final else {}),  # gymnasium's
    }
    return finish_status(summary)


def _agents(run: Any, scenario: Any, counters: dict[str, dict[str, int]],
            learned_files: dict[str, Path]) -> dict[str, AgentRecord]:
    """What the run left of each agent, for the mechanisms' entries of the summary."""
    def learned(a: str) -> str | None:
        return ("\n".join(run.learned.get(a, ())) if run.learned.get(a) or a in learned_files
                else None)
    return {a: AgentRecord(state=run.states[a].to_dict() if a in run.states else {},
                           memory=run.memory.get(a) or {}, learned=learned(a),
                           learned_file=str(learned_files.get(a, "")),
                           counters=counters.get(a, {}))
            for a in {*scenario.agent_ids, *run.memory, *run.states}}
