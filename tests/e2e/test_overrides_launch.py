"""`--set KEY=VALUE` on a real `teleo launch` (issue 25, "Launch-time overrides"): the world
and the goal-entry process, which read the scenario themselves, run the changed one (the
launch's trace is byte for byte that of `teleo simulate` with the same `--set`, and not that
of the file), the summary and the run record say what was applied; and `launch`, `simulate`
and `check` refuse a bad one in one line, before anything starts."""

from __future__ import annotations

import json

import pytest
from e2e_helpers import HOLD_SPEED, Teleo

from tools.records.run_record import RunRecord

SETS = ("--set", "world.pedestrians=0", "--set", "run.cycles=14", "--set", "goals.1.priority=4",
        "--set", f"agents.ME.program={HOLD_SPEED.with_name('hold_speed.tlp')}")


def test_a_launch_runs_the_scenario_as_set(tmp_path):
    teleo = Teleo(tmp_path)
    done = teleo("launch", str(HOLD_SPEED), *SETS, "--summary", str(tmp_path / "l.json"),
                 timeout=240)
    assert done.returncode == 0, done.stdout + done.stderr
    applied = ["world.pedestrians=0", "run.cycles=14", "goals.1.priority=4",
               f"agents.ME.program={HOLD_SPEED.with_name('hold_speed.tlp')}"]
    assert f"  --set: {', '.join(applied)}" in done.stdout.splitlines()
    summary = json.loads((tmp_path / "l.json").read_text())
    assert summary["overrides"] == applied and summary["cycles"] == 14
    assert [(g["id"], g["priority"]) for g in summary["goals"]] == [("g1", 4)]  # goal-entry's
    meta = RunRecord(tmp_path / "runs" / summary["run"] / "record.mcap").meta["teleo.run"]
    assert json.loads(meta["overrides"]) == applied
    sim = teleo("simulate", str(HOLD_SPEED), *SETS, "--no-record", "--trace",
                str(tmp_path / "sim.jsonl"), "--json")
    assert sim.returncode == 0, sim.stderr
    assert json.loads(sim.stdout)["overrides"] == applied
    launched = (tmp_path / "runs" / summary["run"] / "trace.jsonl").read_text()
    assert launched == (tmp_path / "sim.jsonl").read_text()         # the world's, as set
    plain = teleo("simulate", str(HOLD_SPEED), "--cycles", "14", "--no-record", "--trace",
                  str(tmp_path / "plain.jsonl"))
    assert plain.returncode == 0 and (tmp_path / "plain.jsonl").read_text() != launched


@pytest.mark.parametrize("command", ["launch", "simulate", "check"])
def test_a_bad_override_is_refused_in_one_line_before_anything_starts(tmp_path, command):
    teleo = Teleo(tmp_path)
    done = teleo(command, str(HOLD_SPEED), "--set", "world.pedestrianz=3", "--set",
                 "agents.YOU.program=x.tlp")
    assert done.returncode == 1 and "Traceback" not in done.stderr, done.stderr
    lines = done.stderr.splitlines()
    first = "Error: " if command != "check" else ""
    assert lines[0] == (f"{first}{HOLD_SPEED}: --set agents.YOU.program=x.tlp: no entry "
                        "'YOU': name one by its id (ME) or its number (1..1)")
    assert lines[1].startswith(f"{HOLD_SPEED}: --set world.pedestrianz=3: [world] unknown keys "
                               "['pedestrianz']; known: [")
    assert lines[2:] == ([f"{HOLD_SPEED}: 2 errors"] if command == "check" else [])
    assert not (tmp_path / "runs").exists() and not (tmp_path / "active").exists()
    good = teleo(command, str(HOLD_SPEED), "--set", "run.cycles=3", timeout=240)
    assert good.returncode == 0, good.stdout + good.stderr
