"""`teleo launch --no-record` keeps its goals' histories (trial 2026-12-04 N6: its summary
said "g1 ME (cruising ME) p5: cancelled" with no history, where the same launch with a
record, and simulate with or without one, give the statuses and their cycles)."""

from __future__ import annotations

import json

from e2e_helpers import HOLD_SPEED


def test_a_launch_without_a_record_gives_the_same_goal_histories_as_one_with(teleo):
    runs = {}
    for name, extra in (("with", ()), ("without", ("--no-record",))):
        out = teleo("launch", str(HOLD_SPEED), "--json", *extra, timeout=300)
        assert out.returncode == 0, out.stderr
        runs[name] = json.loads(out.stdout)
    assert runs["without"]["record"] is None
    histories = {name: [g["history"] for g in s["goals"]] for name, s in runs.items()}
    assert histories["with"] and all(histories["with"])
    assert histories["without"] == histories["with"]
