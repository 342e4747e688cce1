"""`teleo launch scenarios/minigrid_doorkey.toml` over the bus (world, perception,
inference, executive and goal entry as processes on zenoh, lockstep): the episode is won and
ends the run, with the same trace as `teleo simulate` (run it under `heavy`)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]
TELEO = str(Path(sys.executable).parent / "teleo")
DOORKEY = ROOT / "scenarios" / "minigrid_doorkey.toml"


def test_a_launch_wins_the_episode_and_traces_as_simulate_does(tmp_path):
    env = {**os.environ, "TELEO_RUN_DIR": str(tmp_path)}
    done = subprocess.run([TELEO, "launch", str(DOORKEY), "--summary",
                           str(tmp_path / "launch.json")], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=240)
    assert done.returncode == 0, done.stdout + done.stderr
    launched = json.loads((tmp_path / "launch.json").read_text())
    episode = launched["episode"]
    assert episode["terminated"] and episode["reward"] > 0 and not episode["truncated"]
    assert launched["status"] == "completed" and launched["cycles"] == episode["steps"] + 1
    assert "episode: terminated True" in done.stdout
    sim = subprocess.run([TELEO, "simulate", str(DOORKEY), "--no-record", "--trace",
                          str(tmp_path / "sim.jsonl")], cwd=ROOT, env=env,
                         capture_output=True, text=True, timeout=240)
    assert sim.returncode == 0, sim.stdout + sim.stderr
    assert Path(launched["trace"]).read_text() == (tmp_path / "sim.jsonl").read_text()
