"""A bounded subset of the fuzz drill for goal requests (bench/faults/fuzz.py, reader "request"):
payload bytes through bus.codec.decode and the goal-entry process's answer, with the demo's
agent and a real store file; none may raise anything but the codec's error."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def load_fuzz():
    spec = importlib.util.spec_from_file_location("fuzz_drill",
                                                  ROOT / "bench" / "faults" / "fuzz.py")
    module = sys.modules["fuzz_drill"] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_fuzzed_goal_requests_are_answered_or_refused_never_a_crash(tmp_path):
    fuzz = load_fuzz()
    tally = fuzz.fuzz("request", fuzz.request_reader(tmp_path), 400, seed=11)
    assert tally.crashes == [], tally.crashes[0][1]
    assert tally.accepted > 0 and tally.refused > 0
    assert (tmp_path / "goals.json").exists()  # accepted changes were saved
