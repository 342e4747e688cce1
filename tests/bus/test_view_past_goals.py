"""A live `teleo view` opened after goals ended lists them (issue 31, N5): the goals that
failed or were cancelled before it opened are in no message it sees, so its feed asks the
goal-entry process (a real one, on the bus) for its list once it knows the run's agents."""

from __future__ import annotations

import json
import time

from test_goal_requests import goals_process

from bus import keys
from bus.messages import Intention, WorldState
from tools.runs.target import Target
from tools.view.feeds import BusFeed
from tools.view.model import ViewModel


def record(gid: str, goal: str, status: str, cycle: int, note: str) -> dict:
    return {"id": gid, "agent": "ME", "goal": goal, "priority": 5, "status": status,
            "posted_cycle": 0, "updated_cycle": cycle, "note": note}


def test_goals_that_ended_before_the_view_opened_are_in_its_table(cfg, run_id, tmp_path):
    store = tmp_path / "goals.json"
    store.write_text(json.dumps({"version": 1, "next_id": 3, "goals": [
        record("g1", "(package-delivered PACKET9)", "failed", 40,
               "no percept mentions PACKET9: is there such an object?"),
        record("g2", "(package-delivered PACKET1)", "cancelled", 50, "")]}))
    with goals_process(cfg, run_id, store) as (node, _proc, _log):
        model = ViewModel(run_id)
        feed = BusFeed(model, Target(cfg, run_id, "test")).start()
        try:
            snap = {"domain": "blocks", "cycle": 60, "time": 6.0, "table": {"columns": 3},
                    "blocks": []}
            decision = {"cycle": 60, "goals": [], "goal_id": "", "path": [], "resources": [],
                        "actions": [], "parallel": [], "why": []}
            end = time.monotonic() + 60
            # until both goals are told (not merely "ME" in the changes: the feed thread
            # makes that entry, then fills it)
            while time.monotonic() < end and len(model.goals.changes.get("ME", {})) < 2:
                node.publish(keys.world_state(run_id),
                             WorldState(node.envelope(60), snap, {}, [], {}))
                node.publish(keys.intention(run_id, "ME"),
                             Intention(node.envelope(60), "ME", decision))
                time.sleep(0.5)
            rows = model.frame(60)["agents"]["ME"]["goals"]
        finally:
            feed.close()
    assert [(r["id"], r["status"], r["failed_at"]) for r in rows] == [("g1", "failed", 40)]
    assert rows[0]["note"] == "no percept mentions PACKET9: is there such an object?"
    assert {gid: [c["status"] for c in ch] for gid, ch in model.goals.changes["ME"].items()} \
        == {"g1": ["failed"], "g2": ["cancelled"]}
