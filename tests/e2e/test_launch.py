"""`teleo launch`: a whole run through real processes, zenoh and physics, in lockstep."""

from __future__ import annotations

import json
import pstats
from pathlib import Path

import pytest
from e2e_helpers import HOLD_SPEED, Teleo


@pytest.fixture(scope="module")
def first_run(tmp_path_factory):
    """One 25-cycle launch of the fixture scenario, shared by the tests below."""
    folder = tmp_path_factory.mktemp("first")
    teleo = Teleo(folder)
    done = teleo("launch", str(HOLD_SPEED), "--cycles", "25",
                 "--summary", str(folder / "summary.json"), "--render", str(folder / "run.png"))
    return folder, done


def test_a_launch_runs_the_cycles_and_writes_the_summary(first_run):
    folder, done = first_run
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["completed"] and summary["cycles"] == 25
    assert summary["mode"] == "lockstep" and summary["seed"] == 3
    assert summary["restarts"] == {}
    assert [(g["id"], g["goal"]) for g in summary["goals"]] == [
        ("g1", "(package-delivered PACKET1)")]
    assert set(summary["law_violations"]["ME"]) >= {"pedestrian_hits", "off_road"}
    assert "goals achieved: 0 of 1" in done.stdout
    assert (folder / "run.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the processes are gone and so is the run's registry file
    assert list((folder / "active").glob("*.json")) == []


def test_the_trace_has_one_line_per_cycle_with_the_agents_actions(first_run):
    folder, _ = first_run
    summary = json.loads((folder / "summary.json").read_text())
    lines = [json.loads(x) for x in Path(summary["trace"]).read_text().splitlines()]
    assert [x["cycle"] for x in lines] == list(range(25))
    # the fixture program presses the gas on cycle 0: the car is standing, too slow
    assert lines[0]["actions"] == {"ME": [["*gas", 10]]}
    # the scenario's scripted event: a pedestrian steps out in front of the car at cycle 5
    assert [(x["cycle"], e["status"]) for x in lines for e in x.get("events", ())] == [
        (5, "done")]


def test_the_same_scenario_twice_gives_identical_traces(first_run, tmp_path):
    folder, _ = first_run
    teleo = Teleo(tmp_path)
    again = teleo("launch", str(HOLD_SPEED), "--cycles", "25",
                  "--summary", str(tmp_path / "summary.json"))
    assert again.returncode == 0, again.stdout + again.stderr
    first = json.loads((folder / "summary.json").read_text())["trace"]
    second = json.loads((tmp_path / "summary.json").read_text())["trace"]
    assert first != second  # two runs, two folders
    assert Path(first).read_text() == Path(second).read_text()


def test_teleo_profile_gives_every_process_its_profile_and_changes_no_trace(first_run,
                                                                             tmp_path):
    folder, _ = first_run
    teleo = Teleo(tmp_path)
    teleo.env["TELEO_PROFILE"] = str(tmp_path / "profiles")
    done = teleo("launch", str(HOLD_SPEED), "--cycles", "25",
                 "--summary", str(tmp_path / "summary.json"))
    assert done.returncode == 0, done.stdout + done.stderr
    files = {p.name.rsplit("-", 1)[0]: p for p in (tmp_path / "profiles").glob("*.prof")}
    assert set(files) >= {"world.process", "agents.processes.goals", "bus.router",
                          "agents.processes.perception", "agents.processes.inference",
                          "agents.processes.executive"}, sorted(files)
    # each file is a cProfile of that process's whole run: the executive decided 25 times
    calls = pstats.Stats(str(files["agents.processes.executive"])).stats
    decides = [v[1] for (path, _, name), v in calls.items()
               if name == "decide" and path.endswith("agents/lang/engine.py")]
    assert decides == [25]
    first = json.loads((folder / "summary.json").read_text())["trace"]
    profiled = json.loads((tmp_path / "summary.json").read_text())["trace"]
    assert Path(profiled).read_text() == Path(first).read_text()


def test_a_bad_scenario_is_refused_before_anything_starts(teleo, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[run]\nmode = "fast"\n[[agents]]\nid = "ME"\nprogram = "x.tlp"\n')
    done = teleo("launch", str(bad))
    assert done.returncode != 0
    assert "mode: expected 'lockstep' or 'realtime', got 'fast'" in done.stderr


def test_a_world_or_program_mistake_is_reported_before_anything_starts(teleo, tmp_path):
    program = HOLD_SPEED.parent / "hold_speed.tlp"
    bad_world = tmp_path / "world.toml"
    bad_world.write_text(f'[world]\nlanes = 3\n[[agents]]\nid = "ME"\nprogram = "{program}"\n')
    done = teleo("launch", str(bad_world))
    assert done.returncode != 0 and "unknown keys ['lanes']" in done.stderr
    broken = tmp_path / "broken.tlp"
    broken.write_text("((at-desired-speed ?self)\n :percepts ((self ?self speed ?speed))\n")
    bad_program = tmp_path / "program.toml"
    bad_program.write_text(f'[[agents]]\nid = "ME"\nprogram = "{broken}"\n')
    done = teleo("launch", str(bad_program))
    assert done.returncode != 0 and f"{broken}:" in done.stderr
    assert not list(tmp_path.glob("runs/*"))  # nothing was started


def test_a_realtime_run_completes_its_cycles(teleo, tmp_path):
    done = teleo("launch", str(HOLD_SPEED), "--cycles", "15", "--mode", "realtime",
                 "--summary", str(tmp_path / "summary.json"))
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["mode"] == "realtime" and summary["cycles"] == 15
    # realtime does not wait: on a busy machine a late stage leaves the car to its safe
    # action for a cycle, and the run then says so and fails (docs/faults.md)
    late = sum(summary["uncontrolled"].values())
    assert (done.returncode, summary["status"]) == ((1, "failed") if late else (0, "completed")), \
        done.stdout + done.stderr
    lines = Path(summary["trace"]).read_text().splitlines()
    assert [json.loads(x)["cycle"] for x in lines] == list(range(15))
