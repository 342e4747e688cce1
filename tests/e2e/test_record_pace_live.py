"""A recorded lockstep run never drops cycles from its record while claiming completion
(drills 2026-12-04 D9: at load 34-46 the recorder lost the world's messages, the world ran
on, and a run whose record lacked 64,734 of 65,712 cycles ended "completed"). The launch's
recorder runs in the launcher, so SIGSTOP of the launcher stops it: the world must hold
back as it would for a stage, and the run end with a whole record or fail."""

from __future__ import annotations

import json
import os
import signal
import time
from pathlib import Path

from e2e_helpers import wait_for
from fault_helpers import cycles, scenario, summary, wait_cycles


def test_a_stopped_recorder_holds_the_world_back_and_the_record_stays_whole(teleo):
    launcher = teleo.start("launch", str(scenario(teleo.run_dir)), "--cycles", "0",
                           "--summary", str(teleo.run_dir / "summary.json"))
    info = teleo.run_info()
    try:
        wait_cycles(info, 20)
        os.kill(launcher.pid, signal.SIGSTOP)   # its recorder thread with it
        time.sleep(20)                          # past the 10 s the world once gave up after
        os.kill(launcher.pid, signal.SIGCONT)
        health = Path(info["run_dir"]) / "health.jsonl"
        assert wait_for(lambda: '"record-wait"' in health.read_text(), 120), \
            "the world never waited for its record"
        wait_cycles(info, cycles(info) + 50, timeout=180)
    finally:
        os.kill(launcher.pid, signal.SIGCONT)
        launcher.send_signal(signal.SIGINT)
        launcher.wait(180)
    s = summary(teleo)
    waits = [json.loads(x) for x in health.read_text().splitlines() if "record-wait" in x]
    assert waits and max(w["seconds"] for w in waits) >= 5.0   # held back, not run on
    assert s["status"] == "failed" or s["record_missing"] == 0, s
    assert s["status"] != "completed" or not s["record_gaps"], s
    world_log = (Path(info["run_dir"]) / "logs" / "world.log").read_text()
    assert "launch.record: malformed" not in world_log   # trial N8: progress at cycle -2
