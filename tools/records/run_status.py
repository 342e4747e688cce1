"""The status of a finished run, launch's or simulate's, from its summary, the failures that
say why, and the exit code (docs/faults.md, "What counts as a failed run"):
- failed (exit 1): an agent was uncontrolled for at least one cycle (its actions did not
  arrive and the world applied its safe action), a process gave up (left down after its
  restarts, or a world that could not resume), a goal could not be kept (the executive
  reported it failed), or the world stopped before its cycles were done for any other reason
  than a stop asked for. A goal still at an impasse at the end (no skill path yet; the
  problem solver may have been working on it) is listed as not achieved, not as failed.
  Goals the goal store lost (a damaged file it could not recover) fail the run too. A
  scenario's `[run] status = "system"` leaves the goals out: a goal not kept is then
  reported (`goals_not_kept`) but fails nothing; a scripted request the goal
  store refused is reported (`requests_refused`) and fails nothing either;
  a run record that lacks cycles fails the run (unless a stop asked for cut its drain
  short);
- interrupted (exit 130): stopped on request (Ctrl-C, `teleo stop`) before its cycles were
  done, with nothing failed; a run without a cycle limit ends this way and counts as completed;
- completed (exit 0): otherwise. Stalls, late stages and restarts that recovered are shown
  but do not fail a run.
"""

from __future__ import annotations

import json
from typing import Any

from tools.records.record_coverage import ranges_text

EXIT_CODES = {"completed": 0, "failed": 1, "interrupted": 130}
_NOT_KEPT = ("failed",)


def finish_status(summary: dict[str, Any], ended: str = "",
                  requested_stop: bool = False) -> dict[str, Any]:
    """Add `failures`, `status` and `completed` to a summary (launch's or simulate's): a run
    is failed when an agent went uncontrolled, a process gave up, a goal could not be kept,
    goals were lost or the world stopped early."""
    summary["failures"] = _failures(summary, ended, requested_stop)
    summary["status"] = _status(summary, requested_stop)
    summary["completed"] = summary["status"] == "completed"
    return summary


def _failures(s: dict[str, Any], ended: str, requested_stop: bool) -> list[str]:
    out = [f"{agent} uncontrolled for {n} cycle(s) (the world applied its safe action)"
           for agent, n in s["uncontrolled"].items()]
    out += [f"{name} gave up (left down after {s['restarts'].get(name, 0)} restart(s))"
            for name in s["left_down"]]
    s["goals_not_kept"] = [
        f"goal {g.get('id')} {g.get('goal')} could not be kept: {g.get('status')}"
        + (f" ({g['note']})" if g.get("note") else "")
        for g in s["goals"] if g.get("status") in _NOT_KEPT]
    if s.get("status_policy", "goals") == "goals":
        out += s["goals_not_kept"]
    out += [f"goal store: {i}" for i in s["goal_store_incidents"] if i.startswith("GOALS LOST")]
    out += [f"scripted event {json.dumps(e['event'], sort_keys=True)} at cycle {e['cycle']} "
            f"refused by the world: {e['reason']}" for e in s.get("events_refused", ())]
    failed = s.get("record_failed")
    if failed:
        gaps = s.get("record_gaps")
        lacks = f"it lacks cycles {ranges_text(gaps)}" if gaps else \
            f"nothing was written from about cycle {failed.get('cycle')} on"
        out.append(f"the run record {s.get('record')} could not be written "
                   f"({failed.get('reason')}): {lacks}")
    elif s.get("record_missing") and not (requested_stop and s.get("record_cut_short")):
        out.append(f"the run record {s.get('record')} lacks the world states of "  # D9
                   f"{s['record_missing']} of {s['cycles']} cycles (cycles "
                   f"{ranges_text(s.get('record_gaps') or [])}): a run that dropped cycles "
                   f"from its record is not complete")
    if ended:
        out.append(ended)
    return out


def _status(s: dict[str, Any], requested_stop: bool) -> str:
    if s["failures"]:
        return "failed"
    wanted = int(s.get("cycles_requested") or 0)
    if wanted and s["cycles"] < wanted and not episode_ended(s):
        if requested_stop:
            return "interrupted"
        s["failures"].append(f"the world stopped at cycle {s['cycles']} of {wanted}: "
                             f"{s['world_reason']}")
        return "failed"
    return "completed"


def episode_ended(s: dict[str, Any]) -> bool:
    """The run ended with its world's episode (terminated or truncated): not early."""
    episode = s.get("episode") or {}
    return bool(episode.get("terminated") or episode.get("truncated"))


def exit_code(summary: dict[str, Any]) -> int:
    """0 completed, 1 failed, 130 interrupted (module doc)."""
    return EXIT_CODES[summary["status"]]
