"""Faults in real launches, with real signals (docs/faults.md): every process is supervised
and comes back where the run was, with the same trace; a run that lost control of its agent
says so and fails; nothing outlives its launcher; Ctrl-C works in any state."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from e2e_helpers import ROOT, TELEO, Teleo, wait_for
from fault_helpers import (
    cycles,
    journal,
    kill_all,
    pids_alive,
    restarted,
    scenario,
    summary,
    trace,
    wait_cycles,
)

from tools.records.run_record import RunRecord

CYCLES = "400"


@pytest.fixture(scope="module")
def reference(tmp_path_factory) -> str:
    """The trace of an undisturbed 400-cycle run of the hold-speed scenario."""
    folder = tmp_path_factory.mktemp("reference")
    teleo = Teleo(folder)
    launcher = teleo.start("launch", str(scenario(folder)), "--cycles", CYCLES)
    info = teleo.run_info()
    assert launcher.wait(180) == 0, teleo.launch_output()
    return trace(info)


def start(teleo: Teleo, *extra: str, **run: object) -> tuple[subprocess.Popen, dict]:
    launcher = teleo.start("launch", str(scenario(teleo.run_dir, **run)), "--summary",
                           str(teleo.run_dir / "summary.json"), *extra)
    return launcher, teleo.run_info()


def killed_once(teleo: Teleo, name: str, *extra: str) -> tuple[dict, dict]:
    """A 400-cycle run whose process ``name`` is SIGKILLed after cycle 150: it must be
    restarted once and the run complete. (run info, summary)."""
    launcher, info = start(teleo, "--cycles", CYCLES, *extra)
    wait_cycles(info, 150)
    os.kill(info["pids"][name], signal.SIGKILL)
    assert launcher.wait(180) == 0, teleo.launch_output()
    s = summary(teleo)
    assert f"{name} exited with code -9: restarted (1)" in teleo.launch_output()
    assert s["restarts"] == {name: 1} and s["status"] == "completed"
    return info, s


def test_a_killed_world_resumes_where_the_run_was_with_the_same_trace(teleo, reference):
    info, s = killed_once(teleo, "world")
    assert "world exited with code -9: restarted (1), resuming" in teleo.launch_output()
    [resumed] = s["world_resumes"]
    assert resumed["cycle"] >= 150 and resumed["checkpoint"] in (100, 200, 300)
    assert resumed["replayed"] == resumed["cycle"] - resumed["checkpoint"]
    assert trace(info) == reference


def test_a_killed_router_is_restarted_and_a_stage_killed_after_rejoins(teleo, reference):
    launcher, info = start(teleo, "--cycles", "0")
    try:
        wait_cycles(info, 50)
        os.kill(info["pids"]["router"], signal.SIGKILL)
        restarted(info, "router")
        listed = teleo("goal", "list")  # a new client reaches the run through the new router
        assert listed.returncode == 0 and "g1" in listed.stdout, listed.stderr
        os.kill(teleo.run_info()["pids"]["ME.inference"], signal.SIGKILL)
        restarted(info, "ME.inference")
        wait_cycles(info, cycles(info) + 20)  # the restarted stage works through the new router
    finally:
        launcher.send_signal(signal.SIGINT)
    assert launcher.wait(60) == 0, teleo.launch_output()
    s = summary(teleo)
    assert s["restarts"] == {"router": 1, "ME.inference": 1} and s["status"] == "completed"
    assert "router exited with code -9: restarted (1) on the same endpoint" in \
        teleo.launch_output()
    lines, ref = trace(info).splitlines(), reference.splitlines()
    assert lines[:len(ref)] == ref[:len(lines)]


def test_a_killed_process_of_an_agents_stages_comes_back_with_the_same_trace(teleo, reference):
    """--agents-per-process: the agent's three stages die together and come back together
    (the executive from its state file), and the lockstep run is the undisturbed one."""
    info, _ = killed_once(teleo, "agents1", "--agents-per-process", "auto")
    assert set(info["pids"]) == {"router", "goals", "agents1", "world"}
    assert trace(info) == reference


@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGHUP])
def test_every_process_follows_its_launcher(teleo, sig):
    launcher, info = start(teleo, "--cycles", "0")
    pids = list(info["pids"].values())
    wait_cycles(info, 20)
    launcher.send_signal(sig)
    launcher.wait(60)
    try:
        assert wait_for(lambda: not pids_alive(pids), 20), pids_alive(pids)
    finally:
        kill_all(pids)


def test_ctrl_c_during_a_stall_stops_the_run_and_counts_its_cycles(teleo):
    launcher, info = start(teleo, "--cycles", CYCLES)
    wait_cycles(info, 60)
    os.kill(info["pids"]["ME.inference"], signal.SIGSTOP)
    try:
        wait_for(lambda: False, 1.0)  # the world now waits for the stopped stage
        launcher.send_signal(signal.SIGINT)
        code = launcher.wait(30)
    finally:
        kill_all(info["pids"].values())
    s = summary(teleo)
    assert code == 130 and s["status"] == "interrupted", teleo.launch_output()
    assert s["cycles"] == cycles(info) >= 60  # drill F6 said "0 cycles"
    assert pids_alive(info["pids"].values()) == []


def test_a_launch_in_the_background_of_a_script_still_takes_ctrl_c(teleo):
    """A non-interactive shell starts background jobs with SIGINT ignored (rough edge 10)."""
    command = f"{TELEO[0]} launch {scenario(teleo.run_dir)} --cycles 0"
    shell = subprocess.Popen(["bash", "-c", f"{command} > {teleo.run_dir}/bg.out 2>&1 & "
                              "echo $!; wait $!"], env=teleo.env, stdout=subprocess.PIPE,
                             text=True)
    pid = int(shell.stdout.readline())
    info = teleo.run_info()
    wait_cycles(info, 10)
    os.kill(pid, signal.SIGINT)
    try:
        assert shell.wait(60) == 0, (teleo.run_dir / "bg.out").read_text()
        assert pids_alive([pid, *info["pids"].values()]) == []
    finally:
        kill_all([pid, *info["pids"].values()])


def test_a_stage_left_down_ends_the_run_at_once_as_failed(teleo):
    launcher, info = start(teleo, "--cycles", "0", respawn={"executive": 0})
    wait_cycles(info, 20)
    os.kill(info["pids"]["ME.executive"], signal.SIGKILL)
    code = launcher.wait(60)
    s = summary(teleo)
    assert code == 1 and s["status"] == "failed", teleo.launch_output()
    assert s["left_down"] == ["ME.executive"]
    assert "ME.executive left down after its restarts: the run cannot go on" in s["failures"]
    assert "ME.executive exited with code -9: left down" in teleo.launch_output()


def test_an_agent_without_actions_gets_the_safe_action_and_the_run_fails(teleo):
    """Realtime does not wait: while inference is stopped the car is braked, cycle by cycle,
    and the summary counts those cycles (drill F1: the car drove on uncontrolled)."""
    launcher, info = start(teleo, "--cycles", "60", "--mode", "realtime")
    wait_cycles(info, 10)
    os.kill(info["pids"]["ME.inference"], signal.SIGSTOP)
    wait_for(lambda: False, 1.0)
    os.kill(info["pids"]["ME.inference"], signal.SIGCONT)
    code = launcher.wait(60)
    s = summary(teleo)
    lost = s["uncontrolled"].get("ME", 0)
    assert lost >= 3 and code == 1 and s["status"] == "failed", teleo.launch_output()
    assert f"ME uncontrolled for {lost} cycle(s) (the world applied its safe action)" in \
        s["failures"]
    braked = sum(1 for line in trace(info).splitlines()
                 if '"ME": [["*brake", 100]]' in line)
    assert braked >= lost


@pytest.mark.parametrize("stage", [
    "ME.inference",
    # the goal entry's stats travel in its goal lists; a stopped one sends none, and the
    # clock, reading them from ME's Actions or the stats sent alone by a process gone idle,
    # names it, not the stages after it
    "goals",
])
def test_a_lockstep_stall_is_reported_and_changes_nothing(teleo, reference, stage):
    launcher, info = start(teleo, "--cycles", CYCLES)
    wait_cycles(info, 80)
    os.kill(info["pids"][stage], signal.SIGSTOP)
    wait_for(lambda: False, 2.0)
    os.kill(info["pids"][stage], signal.SIGCONT)
    assert launcher.wait(180) == 0, teleo.launch_output()
    s = summary(teleo)
    assert s["stalls"] and s["stalls"][0]["stages"] == [stage], s["stalls"]
    assert s["stalls"][0]["seconds"] >= 1.0 and s["status"] == "completed"
    assert f"stalls: 1 ({stage}" in teleo.launch_output() or len(s["stalls"]) > 1
    assert trace(info) == reference
    assert [e["event"] for e in journal(info)][:1] == ["ready"]


def test_the_launcher_drill_runs_as_a_user_would_run_it(tmp_path):
    """bench/faults/drills.py stays runnable: its launcher drill, on the small scenario."""
    done = subprocess.run([sys.executable, "bench/faults/drills.py", "launcher", "--scenario",
                           str(scenario(tmp_path))], cwd=ROOT, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    rows = [line for line in done.stdout.splitlines() if "drill=" in line]
    assert [r.split("  ")[1] for r in rows] == ["drill=SIGKILL launcher",
                                                "drill=SIGHUP launcher"]
    assert all("left=0" in r and "all_gone_ms=None" not in r for r in rows)


def test_a_killed_router_costs_the_run_record_nothing(teleo, reference):
    """Drill N1: after a router kill the record lacked about half of the demo's cycles and
    the summary dated goals to the cycle after the gap. The launcher's recorder is a peer
    of the run's processes, which keep their links to each other: every cycle is recorded."""
    launcher, info = start(teleo, "--cycles", CYCLES)
    wait_cycles(info, 100)
    os.kill(info["pids"]["router"], signal.SIGKILL)
    assert launcher.wait(180) == 0, teleo.launch_output()
    s = summary(teleo)
    assert s["restarts"] == {"router": 1} and trace(info) == reference
    assert s["record_missing"] == 0 and s["record_gaps"] == [], teleo.launch_output()
    held: dict[str, set[int]] = {}
    for key, rec in RunRecord(Path(s["record"])).records():
        held.setdefault(key.split("/", 2)[2], set()).add(rec["env"]["cycle"])
    assert held.pop("world/static") == {-1}   # once a run, outside the cycles (issue 35)
    # issue 36: ME's stages' stats travel in their outputs, the goal entry's in its goal
    # lists, alone only from one gone idle after a cycle (some cycles, or none)
    for process in ("goals", "ME.perception", "ME.inference", "ME.executive"):
        assert held.pop(f"stats/{process}", set()) <= set(range(int(CYCLES)))
    assert {k for k, cycles in held.items() if cycles != set(range(int(CYCLES)))} == set()
    assert len(held) == 7  # the world state, ME's percepts, beliefs, intention, actions and
    #                        goal list, the world's stats
    assert all("after" not in h for g in s["goals"] for h in g["history"])


def sigint_taken(pid: int) -> bool:
    """Whether `pid` is the launcher (no longer the shell that starts it) and has its own
    SIGINT handler set."""
    try:
        argv = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    caught = next(int(x.split()[1], 16) for x in status.splitlines() if x.startswith("SigCgt"))
    return argv[0] != b"sh" and b"launch" in argv and bool(caught & 1 << signal.SIGINT - 1)


def test_a_sigint_while_the_launcher_starts_stops_it_before_it_starts_anything(teleo):
    """Drill d1c: a launch started with `&` from `sh -c` has SIGINT ignored (POSIX); one
    sent while it was still importing was lost and the run went on. It is kept now, from
    the first moment the command runs, and the launch ends at once, having started nothing."""
    out = teleo.run_dir / "bg.out"
    shell = subprocess.Popen(["sh", "-c", f"{TELEO[0]} launch {scenario(teleo.run_dir)} "
                              f"--cycles 0 > {out} 2>&1 & echo $!; wait $!; echo $?"],
                             env=teleo.env, stdout=subprocess.PIPE, text=True)
    pid = int(shell.stdout.readline())
    try:
        assert wait_for(lambda: sigint_taken(pid), 60)
        os.kill(pid, signal.SIGINT)
        code = shell.communicate(timeout=60)[0].split()[-1]
    finally:
        kill_all([pid])
    assert code == "130", out.read_text()
    assert out.read_text().splitlines()[-1] == ("interrupted before the run started: no "
                                                "process was started")
    assert not (teleo.run_dir / "runs").exists() and teleo.run_files() == []


def test_a_second_signal_while_the_run_stops_does_not_break_off_the_stop(teleo):
    """Ctrl-C pressed again, or a `teleo stop` after a Ctrl-C: the stop still goes to its
    end (registry entry, record, summary) and says nothing of a KeyboardInterrupt."""
    launcher, info = start(teleo, "--cycles", "0")
    try:
        wait_cycles(info, 20)
        launcher.send_signal(signal.SIGINT)
        assert wait_for(lambda: "interrupted: stopping the run" in teleo.launch_output(), 30)
        launcher.send_signal(signal.SIGINT)
        launcher.send_signal(signal.SIGTERM)
        assert launcher.wait(60) == 0, teleo.launch_output()
    finally:
        kill_all(info["pids"].values())
    s = summary(teleo)
    assert s["status"] == "completed" and s["cycles"] == cycles(info)
    assert "Traceback" not in teleo.launch_output() and teleo.run_files() == []
    assert pids_alive(info["pids"].values()) == []
