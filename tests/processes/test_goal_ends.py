"""Goals that end, in scenarios' [[goals]] (issue 34, item 2): `once = true` and
`deadline = N`, run by `teleo simulate` (the goal-entry store, the goal sync and the engine a
launch uses): a once goal is not pursued again when undone, one past its deadline fails with
its reason; a bad value is one line naming the field."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TELEO = str(Path(sys.executable).parent / "teleo")
FIGURE3 = (ROOT / "scenarios" / "blocks_figure3.toml").read_text().replace(
    '"programs/blocks.tlp"', f'"{ROOT / "programs" / "blocks.tlp"}"').replace(
    "cycles = 8", "cycles = 12")
D_ON_A = '\n[[events]]\nat_cycle = 6\nkind = "add"\nblock = "D"\non = "A"\n'


def _simulate(tmp_path: Path, name: str, extra: str) -> tuple[subprocess.CompletedProcess,
                                                              list[dict]]:
    scenario = tmp_path / f"{name}.toml"
    scenario.write_text(FIGURE3.replace('priority = 1\n', f'priority = 1\n{extra}\n'))
    trace = tmp_path / f"{name}.jsonl"
    done = subprocess.run([TELEO, "simulate", str(scenario), "--trace", str(trace), "--json",
                           "--no-record"], cwd=ROOT, capture_output=True, text=True,
                          timeout=120, env={**os.environ, "TELEO_RUN_DIR": str(tmp_path)})
    lines = [json.loads(x) for x in trace.read_text().splitlines()] if trace.exists() else []
    return done, [a for line in lines for a in line["actions"].get("ME", [])]


def test_a_once_goal_undone_by_the_world_is_left_undone(tmp_path):
    kept, kept_acts = _simulate(tmp_path, "kept", D_ON_A)
    once, once_acts = _simulate(tmp_path, "once", "once = true" + D_ON_A)
    assert kept.returncode == 0 and once.returncode == 0, kept.stderr + once.stderr
    first = [["*unstack", "C", "B"], ["*putdown", "C", "T"], ["*unstack", "B", "A"]]
    assert once_acts == first                       # D on A at cycle 6: nothing more
    assert kept_acts[:3] == first and ["*unstack", "D", "A"] in kept_acts[3:]
    goal = json.loads(once.stdout)["goals"][0]
    assert goal["status"] == "achieved", goal


def test_a_goal_past_its_deadline_fails_with_the_reason(tmp_path):
    late, acts = _simulate(tmp_path, "late", "deadline = 2")
    goal = json.loads(late.stdout)["goals"][0]
    assert goal["status"] == "failed", goal
    assert "(clear A) not achieved by cycle 2, its deadline" in goal["note"], goal
    # cycle 0 an impasse (the problem solver), cycle 1 an action, cycle 2 over: not pursued
    assert acts == [["*unstack", "C", "B"]]
    met, _ = _simulate(tmp_path, "met", "deadline = 9")
    assert json.loads(met.stdout)["goals"][0]["status"] == "achieved"
    bad, _ = _simulate(tmp_path, "bad", "deadline = 0\nonce = 1")
    assert bad.returncode != 0 and "[[goals]] #1.deadline: expected >= 1, got 0" in bad.stderr
    assert "[[goals]] #1.once: expected" in bad.stderr
