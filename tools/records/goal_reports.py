"""Each goal of a run's summary with its history: the goal store's records reconciled with
the status changes the run record saw (or, for a launch without a record, the goal watch's
file), statuses as users see them."""

from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import Any

from tools.records.run_record import GOAL_HISTORY, RECORD_FILE, RecordError, RunRecord

log = logging.getLogger(__name__)

USER_STATUS = {"satisfied": "achieved"}
"""The engine's status words as the goal-entry process reports user goals (goal_store.py)."""


def with_history(goals: list[dict[str, Any]], run_dir: Path,
                 record: RunRecord | None = None) -> list[dict[str, Any]]:
    """The summary's goals (the goal store's records), each with "history": [{"cycle",
    "status"}] of its status changes in the run record (statuses as users see them:
    satisfied -> achieved); [] without one. Only what is known is told (`reconcile`)."""
    if record is None:
        path = Path(run_dir) / RECORD_FILE
        try:
            record = RunRecord(path) if path.is_file() else None
        except RecordError as exc:
            log.warning("no goal history: %s", exc)
    try:
        history = record.goal_history() if record is not None else _watched(run_dir)
    except RecordError as exc:
        log.warning("no goal history: %s", exc)
        history = {}
    return goals_with_history(goals, history)


def _watched(run_dir: Path) -> dict[str, Any]:
    """The goal histories a launch without a record kept (GOAL_HISTORY), or {}."""
    try:
        doc = json.loads((Path(run_dir) / GOAL_HISTORY).read_text())
    except (OSError, ValueError):
        return {}
    return doc if isinstance(doc, dict) else {}


def goals_with_history(goals: list[dict[str, Any]],
                       history: dict[str, dict[str, list[dict[str, Any]]]]
                       ) -> list[dict[str, Any]]:
    """``goals`` each with "history" from GoalHistory.changes (``with_history``); only what
    is known is told (`reconcile`)."""
    return [reconcile(g, history.get(g.get("agent"), {}).get(g.get("id"), []))
            for g in goals]


def reconcile(goal: dict[str, Any], changes: list[dict[str, Any]]) -> dict[str, Any]:
    """One goal of the goal store with its history from the record's `changes`:
    - a change the record saw only after a gap keeps "after" (it came at a cycle after that
      one, up to "cycle"), unless the goal store, which saw every cycle, dates that status
      within the gap ("source": "goal store");
    - a final status the record never saw (its end was lost) is added from the store;
    - a status the record saw after the store's last change (a store that could not be
      saved since: a full disk) is the goal's status, with a note saying so; but never over
      a failure the store holds (failed is final: a failed run is never reported completed)."""
    out = []
    for c in changes:
        entry = {"cycle": c["cycle"], "status": USER_STATUS.get(c["status"], c["status"])}
        if "after" in c:
            entry["after"] = c["after"]
        out.append(entry)
    status, when = goal.get("status"), goal.get("updated_cycle")
    if not out or not isinstance(when, int):
        return {**goal, "history": out}
    last = out[-1]
    if last["status"] == status and "after" in last and last["after"] < when <= last["cycle"]:
        out[-1] = {"cycle": when, "status": status, "source": "goal store"}
    elif last["status"] != status and last["cycle"] > when and status != "failed":
        return {**goal, "status": last["status"], "updated_cycle": last["cycle"],
                "note": f"from the run record: the goal store was last saved with {status} "
                        f"(cycle {when})", "history": out}
    elif last["status"] != status and when >= last["cycle"]:
        out.append({"cycle": when, "status": status, "source": "goal store"})
    return {**goal, "history": out}


def history_text(history: list[dict[str, Any]], most: int = 8) -> str:
    """" (active 0, achieved 213)": a goal's status changes for a one-line summary; a change
    seen after a gap in the record reads "achieved 201..486" (at one of those cycles)."""
    if not history:
        return ""
    parts = [f"{h['status']} {h['after'] + 1}..{h['cycle']}" if "after" in h
             else f"{h['status']} {h['cycle']}" for h in history]
    if len(parts) > most:
        parts = parts[:most - 1] + [f"... {len(parts) - most} more", parts[-1]]
    return " (" + ", ".join(parts) + ")"
