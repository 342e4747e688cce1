"""`teleo record info RECORD` summarises a real run record (issue 34, item 3): its run,
cycles, duration, agents, channels with their message counts and each goal's final status,
as text and as JSON; a record cut short is read as far as it goes; bad input is one line."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TELEO = str(Path(sys.executable).parent / "teleo")


def _teleo(run_dir: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([TELEO, *args], cwd=ROOT, capture_output=True, text=True, timeout=120,
                          env={**os.environ, "TELEO_RUN_DIR": str(run_dir)})


@pytest.fixture(scope="module")
def figure3(tmp_path_factory) -> tuple[Path, Path]:
    """Figure 3 of the blocks world simulated: (the runs folder, its record)."""
    run_dir = tmp_path_factory.mktemp("runs")
    done = _teleo(run_dir, "simulate", str(ROOT / "scenarios" / "blocks_figure3.toml"))
    assert done.returncode == 0, done.stderr
    (record,) = (run_dir / "runs").glob("*/record.mcap")
    return run_dir, record


def test_record_info_counts_each_channel_and_says_the_goals_end(figure3):
    run_dir, record = figure3
    done = _teleo(run_dir, "record", "info", str(record.parent), "--json")
    assert done.returncode == 0, done.stderr
    s = json.loads(done.stdout)
    run = record.parent.name
    assert s["run"] == run and s["domain"] == "blocks" and s["source"] == "simulate"
    assert s["cycles"] == {"first": 0, "last": 7, "states_held": [[0, 7]]}
    assert s["agents"] == ["ME"] and not s["truncated"]
    counts = {c["key"].removeprefix(f"teleo/{run}/"): (c["kinds"], c["count"])
              for c in s["channels"]}
    assert counts["world/state"] == (["WorldState"], 8)
    assert counts["agent/ME/actions"] == (["Actions"], 8)
    assert counts["world/static"] == (["WorldStatic"], 1)   # the static part, once a run
    assert s["messages"] == sum(n for _, n in counts.values()) == 81
    assert s["world_s"] == 3.5   # 7 steps of the blocks world's 0.5 s
    (goal,) = s["goals"]["ME"]
    assert (goal["id"], goal["goal"], goal["status"], goal["cycle"]) == \
        ("g1", "(clear A)", "satisfied", 4)
    text = _teleo(run_dir, "record", "info", run)   # by run id, as a person reads it
    assert text.returncode == 0, text.stderr
    assert "cycles:   0-7 (world states held: 0-7)" in text.stdout
    assert "messages: 81 on 11 channels" in text.stdout
    assert f"  8  WorldState     teleo/{run}/world/state" in text.stdout
    assert "  ME g1 (clear A): satisfied at cycle 4" in text.stdout


def test_a_record_cut_short_is_read_as_far_as_it_goes(figure3, tmp_path):
    run_dir, record = figure3
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(record.read_bytes()[: record.stat().st_size * 2 // 3])
    done = _teleo(run_dir, "record", "info", str(cut), "--json")
    assert done.returncode == 0, done.stderr
    s = json.loads(done.stdout)
    assert s["truncated"] and 0 < s["messages"] <= 81


def test_bad_input_is_one_line(figure3, tmp_path):
    run_dir, _ = figure3
    missing = _teleo(run_dir, "record", "info", str(tmp_path / "nothing"))
    assert missing.returncode == 1
    assert missing.stderr.startswith(f"Error: record info: {tmp_path / 'nothing'}: no run "
                                     "record here") and missing.stderr.count("\n") == 1
    (tmp_path / "notes.txt").write_text("not a record")
    junk = _teleo(run_dir, "record", "info", str(tmp_path / "notes.txt"))
    assert junk.returncode == 1 and junk.stderr == \
        f"Error: record info: {tmp_path / 'notes.txt'}: not a readable run record (not MCAP)\n"
    assert _teleo(run_dir, "record", "info").returncode == 2   # RECORD is needed
