"""bench/speed/engine_replay.py end to end on a few of the demo's cycles: a real simulation
recorded, then replayed in real processes through this tree's engine twice (the tree against
itself), and its usage error for a folder that is no teleo tree."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

from tests.bench.scripts import run_script

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench" / "speed" / "engine_replay.py"


def bench(*args: str) -> subprocess.CompletedProcess:
    return run_script(BENCH, *args, timeout=300)


def test_a_short_replay_alternates_the_trees_and_prints_their_ratio():
    done = bench("--against", str(ROOT), "--rounds", "2", "--reps", "2", "--cycles", "12")
    assert done.returncode == 0, done.stderr
    rounds = [line.split(":")[1].split()[0] for line in done.stdout.splitlines()
              if line.startswith("round ")]
    assert rounds == ["this", "against", "against", "this"]   # alternating, round by round
    for line in done.stdout.splitlines():
        if line.startswith("round "):
            assert len(re.findall(r"\d+\.\d{3}", line)) == 2   # one median per replay
    last = done.stdout.splitlines()[-1]
    assert re.search(r"\(median of 4 replays each\): this / against \d+\.\d\dx", last), last


def test_a_folder_that_is_no_teleo_tree_is_refused_by_name(tmp_path):
    done = bench("--against", str(tmp_path))
    assert done.returncode == 2
    assert f"{tmp_path} holds no agents/lang/engine.py" in done.stderr
    assert "Traceback" not in done.stderr
