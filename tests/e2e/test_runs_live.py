"""Finding and stopping runs (rough edges 3 and 4): two launches side by side each keep their
own run file, `teleo ps` lists both with their processes, every tool finds a run the same
way from any directory and says which it reached, `teleo stop` stops one run and cleans up
after a launcher that died; a run stopped by a signal leaves no entry, and the next launch
removes those a killed launcher left."""

from __future__ import annotations

import json
import os
import signal
import subprocess

import pytest
from e2e_helpers import TELEO, Teleo, wait_for
from fault_helpers import kill_all, pids_alive, scenario, wait_cycles

from tools.runs import runfile


def anywhere(teleo: Teleo, *args: str) -> subprocess.CompletedProcess:
    """`teleo ...` run from / (not the repository, not the run folder)."""
    return subprocess.run([*TELEO, *args], cwd="/", env=teleo.env, capture_output=True,
                          text=True, timeout=60)


def ps(teleo: Teleo) -> dict[str, dict]:
    done = anywhere(teleo, "ps", "--json")
    assert done.returncode == 0, done.stderr
    return {d["run"]: d for d in map(json.loads, done.stdout.splitlines())}


def test_two_runs_side_by_side_are_listed_found_by_name_and_stopped_one_by_one(tmp_path):
    teleo = Teleo(tmp_path)
    path = scenario(tmp_path)
    first = teleo.start("launch", str(path), "--cycles", "0")
    info = teleo.run_info()
    second_out = (tmp_path / "second.out").open("w")
    second = subprocess.Popen([*TELEO, "launch", str(path), "--cycles", "0"], env=teleo.env,
                              cwd="/", stdout=second_out, stderr=subprocess.STDOUT)
    every = []
    try:
        assert wait_for(lambda: len(teleo.run_files()) == 2, 90)
        runs = ps(teleo)
        other = next(r for r in runs if r != info["run"])
        every = [p["pid"] for r in runs.values() for p in r["processes"].values()]
        assert all(r["running"] for r in runs.values())
        assert all(p["alive"] for r in runs.values() for p in r["processes"].values())
        assert set(runs[other]["processes"]) == set(info["pids"])
        # the first run's file is still its own
        assert json.loads((tmp_path / "active" / f"{info['run']}.json").read_text())[
            "pid"] == first.pid
        unsure = anywhere(teleo, "goal", "list")
        assert unsure.returncode != 0 and "2 runs are running" in unsure.stderr
        named = anywhere(teleo, "goal", "list", "--run", other)
        assert named.returncode == 0 and "g1" in named.stdout
        assert named.stderr.startswith(f"run {other} (router tcp/127.0.0.1:")
        wait_cycles(info, 5)
        echoed = anywhere(teleo, "echo", "world/state", "--count", "2", "--run", info["run"])
        assert echoed.returncode == 0, echoed.stderr
        assert [json.loads(x)["kind"] for x in echoed.stdout.splitlines()] == ["WorldState"] * 2
        assert f"listening on teleo/{info['run']}/world/state" in echoed.stderr
        stopped = anywhere(teleo, "stop", info["run"])
        assert stopped.returncode == 0 and f"run {info['run']} stopped" in stopped.stdout
        assert first.wait(30) == 0
        assert pids_alive(info["pids"].values()) == []
        assert list(ps(teleo)) == [other] and second.poll() is None
        assert anywhere(teleo, "stop").returncode == 0  # the only one left
        assert second.wait(30) == 0
    finally:
        for proc in (first, second):
            if proc.poll() is None:
                proc.kill()
        second_out.close()
        kill_all(every)


def test_stop_cleans_up_what_a_killed_launcher_left(teleo):
    launcher = teleo.start("launch", str(scenario(teleo.run_dir)), "--cycles", "0")
    info = teleo.run_info()
    stuck = info["pids"]["ME.inference"]
    try:
        wait_cycles(info, 10)
        os.kill(stuck, signal.SIGSTOP)  # a stopped process cannot follow its launcher
        launcher.kill()
        launcher.wait(30)
        assert wait_for(lambda: pids_alive(info["pids"].values()) == [stuck], 20)
        listed = anywhere(teleo, "ps")
        assert "STALE (launcher gone)" in listed.stdout
        assert f"ME.inference             pid {stuck:<8} up" in listed.stdout
        done = anywhere(teleo, "stop")
        assert done.returncode == 0, done.stderr
        assert "stopped 1 process(es)" in done.stdout
        assert pids_alive([stuck]) == [] and teleo.run_files() == []
    finally:
        kill_all(info["pids"].values())


def test_stop_of_a_run_nothing_is_left_of_says_so(teleo):
    launcher = teleo.start("launch", str(scenario(teleo.run_dir)), "--cycles", "0")
    info = teleo.run_info()
    try:
        wait_cycles(info, 5)
        launcher.kill()           # its processes follow it (each watches its launcher)
        launcher.wait(30)
        assert wait_for(lambda: pids_alive(info["pids"].values()) == [], 30)
        done = anywhere(teleo, "stop")
        assert done.returncode == 0, done.stderr
        assert done.stdout.strip() == (f"run {info['run']} was not running (its launcher "
                                       f"{info['pid']} is gone); its stale entry is removed")
        assert teleo.run_files() == []
    finally:
        kill_all(info["pids"].values())


def test_tools_say_where_they_looked_when_no_run_is_there(teleo):
    done = anywhere(teleo, "goal", "list")
    assert done.returncode != 0
    assert f"no running teleo launch found in {teleo.run_dir / 'active'}" in done.stderr
    assert "Traceback" not in done.stderr
    echoed = anywhere(teleo, "echo", "**", "--seconds", "1")
    assert echoed.returncode != 0 and "no running teleo launch found" in echoed.stderr


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_a_run_stopped_by_a_signal_takes_its_entry_out_of_the_registry(teleo, sig):
    """Trial #1: a run stopped by Ctrl-C or SIGTERM (the tutorial's `kill -TERM %1`) stayed
    in `teleo ps` as STALE, and a bare `teleo stop` then refused. Only SIGKILL leaves one."""
    launcher = teleo.start("launch", str(scenario(teleo.run_dir)), "--cycles", "0")
    info = teleo.run_info()
    try:
        wait_cycles(info, 10)
        launcher.send_signal(sig)
        assert launcher.wait(60) == 0, teleo.launch_output()
    finally:
        kill_all(info["pids"].values())
    assert teleo.run_files() == []
    assert anywhere(teleo, "ps").stdout.startswith("no runs registered in ")
    stopped = anywhere(teleo, "stop")
    assert stopped.returncode == 1 and "no runs registered in " in stopped.stderr


def test_the_next_launch_removes_the_entries_of_runs_nothing_is_left_of(teleo, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(teleo.run_dir))
    gone = subprocess.Popen(["true"])
    gone.wait()
    runfile.write(runfile.RunInfo("hold-speed-0ld0ne", "tcp/127.0.0.1:1", gone.pid, ("ME",),
                                  str(teleo.run_dir / "runs" / "hold-speed-0ld0ne"),
                                  "hold.toml", started=1.0))
    launcher = teleo.start("launch", str(scenario(teleo.run_dir)), "--cycles", "30")
    assert launcher.wait(120) == 0, teleo.launch_output()
    assert (f"removed the stale entry of run hold-speed-0ld0ne (its launcher {gone.pid} is "
            "gone, and nothing of the run is left)") in teleo.launch_output()
    assert teleo.run_files() == []
