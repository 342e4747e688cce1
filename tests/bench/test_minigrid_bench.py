"""bench/minigrid/minigrid.py's names: a short name gets MiniGrid's prefix and version, a name
with its own version keeps it, and a name nothing registers is refused in one line before any
run starts."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench" / "minigrid" / "minigrid.py"


def load_bench():
    spec = importlib.util.spec_from_file_location("minigrid_bench", BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_short_name_gets_its_prefix_and_version_and_keeps_its_own() -> None:
    env_id = load_bench().env_id
    assert env_id("DoorKey-8x8") == "MiniGrid-DoorKey-8x8-v0"
    assert env_id("ObstructedMaze-Full-v1") == "MiniGrid-ObstructedMaze-Full-v1"
    assert env_id("BabyAI-GoToSeq-v0") == "BabyAI-GoToSeq-v0"


def test_an_unregistered_name_is_refused_in_one_line() -> None:
    done = subprocess.run([sys.executable, str(BENCH), "--envs", "DoorKey-8x8,Nope-v1",
                           "--seeds", "0"], capture_output=True, text=True, timeout=120,
                          cwd=ROOT)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.splitlines()[-1].endswith("--envs: not registered: MiniGrid-Nope-v1")
    assert "Traceback" not in done.stderr
