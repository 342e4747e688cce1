"""The run registry (tools/runs/runfile.py): one file per run, readable by its owner only, found
the same way by every tool from any directory; a second run never takes over the first's
file; a run whose launcher has exited is told apart, and its entry removed (`teleo ps
--prune`, the next launch) once nothing of it is left, or stopped with `teleo stop --all`."""

from __future__ import annotations

import signal
import stat
import subprocess
import sys
from dataclasses import replace

import pytest
from click.testing import CliRunner

from tools.cli import cli
from tools.runs import runfile


@pytest.fixture
def registry(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    return tmp_path / "active"


@pytest.fixture
def launcher():
    """A live process standing in for a launcher (only its pid matters here)."""
    proc = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    yield proc.pid
    proc.kill()
    proc.wait()


def exited_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def info(run: str, pid: int, started: float = 1.0) -> runfile.RunInfo:
    return runfile.RunInfo(run, "tcp/127.0.0.1:1", pid, ("ME",), f"/runs/{run}", "s.toml",
                           started=started)


def test_each_run_has_its_own_file_readable_by_its_owner_only(registry, launcher):
    runfile.write(info("a", launcher))
    runfile.write(info("b", launcher, started=2.0))
    assert sorted(p.name for p in registry.iterdir()) == ["a.json", "b.json"]
    assert stat.S_IMODE(registry.stat().st_mode) == 0o700
    assert stat.S_IMODE((registry / "a.json").stat().st_mode) == 0o600
    assert [i.run for i, up in runfile.all_runs()] == ["a", "b"]
    runfile.remove(info("a", launcher))
    assert [i.run for i, _ in runfile.all_runs()] == ["b"]


def test_find_takes_the_only_run_or_the_one_named(registry, launcher):
    runfile.write(info("a", launcher))
    assert runfile.find().run == "a"
    runfile.write(info("b", launcher, started=2.0))
    with pytest.raises(runfile.NoRunningLaunch, match=r"2 runs are running \(a, b\)"):
        runfile.find()
    assert runfile.find("b").run == "b"
    with pytest.raises(runfile.NoRunningLaunch, match="no run 'c' in .*active"):
        runfile.find("c")


def test_a_run_whose_launcher_exited_is_stale(registry):
    runfile.write(info("gone", exited_pid()))
    with pytest.raises(runfile.NoRunningLaunch, match="1 stale: see `teleo ps`"):
        runfile.find()
    with pytest.raises(runfile.NoRunningLaunch, match="has exited"):
        runfile.find("gone")
    assert runfile.all_runs()[0][1] is False


def test_without_teleo_run_dir_the_registry_is_the_users_own(tmp_path, launcher,
                                                               monkeypatch):
    monkeypatch.delenv("TELEO_RUN_DIR", raising=False)
    monkeypatch.delenv("XDG_RUNTIME_DIR", raising=False)
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    here, there = tmp_path / "here", tmp_path / "there"
    here.mkdir()
    there.mkdir()
    monkeypatch.chdir(here)
    runfile.write(info("a", launcher))
    monkeypatch.chdir(there)
    assert runfile.find().run == "a"
    assert runfile.registry() == tmp_path / "home" / ".local" / "state" / "teleo" / "active"
    assert runfile.base_dir() == there / "out"  # run folders go where the launch runs


def test_a_secured_run_gives_tools_the_operators_credentials(registry, launcher):
    runfile.write(info("a", launcher))
    assert runfile.bus_config(runfile.find()).credentials == ""
    secured = runfile.RunInfo("s", "tls/127.0.0.1:1", launcher, ("ME",), "/r", "s.toml",
                              credentials="/r/secrets/operator.cred.json")
    cfg = runfile.bus_config(secured)
    assert cfg.mode.value == "client" and cfg.credentials.endswith("operator.cred.json")


@pytest.fixture
def leftover():
    """A process left of a run whose launcher is gone: its command line names the run."""
    proc = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)", "run-left"])
    yield proc
    proc.kill()
    proc.wait()


def stale_runs(launcher: int, leftover: int) -> None:
    """Three entries: one running, one stale with nothing left, one stale with a process."""
    runfile.write(info("live", launcher))
    runfile.write(info("run-gone", exited_pid(), started=2.0))
    runfile.write(replace(info("run-left", exited_pid(), started=3.0),
                          pids={"ME.inference": leftover, "world": exited_pid()}))


def test_prune_removes_the_stale_entries_nothing_is_left_of(registry, launcher, leftover):
    stale_runs(launcher, leftover.pid)
    removed, kept = runfile.prune()
    assert [i.run for i in removed] == ["run-gone"] and [i.run for i in kept] == ["run-left"]
    assert [(i.run, up) for i, up in runfile.all_runs()] == [("live", True),
                                                             ("run-left", False)]
    assert runfile.leftovers(kept[0]) == [leftover.pid]


def test_ps_prune_says_which_entries_it_removed_and_which_it_kept(registry, launcher,
                                                                    leftover):
    stale_runs(launcher, leftover.pid)
    done = CliRunner().invoke(cli, ["ps", "--prune"])
    assert done.exit_code == 0, done.output
    lines = done.output.splitlines()
    assert lines[0].startswith("removed the stale entry of run run-gone (its launcher ")
    assert lines[1].startswith("kept the stale entry of run run-left: its launcher ")
    assert f"(pids {leftover.pid}); `teleo stop run-left` stops them" in lines[1]
    assert "live  launcher" in done.output and "run-gone" not in "".join(lines[2:])


def test_stop_all_stops_what_is_left_of_every_run(registry, leftover):
    runfile.write(info("run-gone", exited_pid()))
    runfile.write(replace(info("run-left", exited_pid(), started=2.0),
                          pids={"ME.inference": leftover.pid}))
    done = CliRunner().invoke(cli, ["stop", "--all"])
    assert done.exit_code == 0, done.output
    assert leftover.wait(10) == -signal.SIGTERM
    assert "stopped 1 process(es) of run-left left without a launcher" in done.output
    assert "run run-gone was not running" in done.output
    assert runfile.all_runs() == []
    both = CliRunner().invoke(cli, ["stop", "--all", "run-left"])
    assert both.exit_code == 2 and "give RUN or --all, not both" in both.output


def test_a_tool_in_another_folder_finds_the_launch_scenarios_program(registry, launcher,
                                                                      tmp_path, monkeypatch):
    """Issue 31 (N4): a launch of `scenarios/driving_demo.toml` from the project's folder
    registered the relative path, and `teleo view` started elsewhere found no program for
    its beliefs panel. The registry keeps the scenario absolute and the launch's folder,
    where the scenario's relative program paths start."""
    from pathlib import Path

    from tools.view.feeds import scenario_of
    from tools.view.programs import Programs

    root = Path(__file__).resolve().parents[2]
    monkeypatch.chdir(root)
    runfile.write(replace(info("a", launcher), scenario="scenarios/driving_demo.toml"))
    monkeypatch.chdir(tmp_path)
    scenario, cwd = scenario_of("a")
    assert (scenario, cwd) == (str(root / "scenarios" / "driving_demo.toml"), str(root))
    programs = Programs()
    programs.from_scenario(scenario, cwd)
    program, source = programs.get("ME")
    assert program is not None, source
    assert source == str(root / "programs" / "driving.tlp")
    programs.saw("ME", {"path": [{"where": "programs/errands.tlp:3:1"}]})  # relative too
    assert str(root / "programs" / "errands.tlp") in programs._candidates["ME"]
