"""`teleo goal` and `teleo inspect` against a running launch, and the kill-and-restart path."""

from __future__ import annotations

import json
import os
import signal
from pathlib import Path

from e2e_helpers import HOLD_SPEED, PARKED, Teleo, interrupt, trace_lines, two_cars, wait_for

PURSUED = {"active", "pending", "suspended", "impasse"}


def goal_statuses(teleo) -> dict[str, str]:
    listed = teleo("goal", "list")
    assert listed.returncode == 0, listed.stderr
    rows = [line.split() for line in listed.stdout.splitlines()[1:]]
    return {row[0]: row[3] for row in rows}


def process_rows(text: str) -> dict[str, dict[str, str]]:
    """The rows of `teleo inspect`'s processes table, by process, by column."""
    lines = [line.replace("┃", "│") for line in text.splitlines()]
    lines = [line for line in lines if line.count("│") >= 6]
    header = [c.strip() for c in lines[0].strip("│ ").split("│")]
    rows = {}
    for line in lines[1:]:
        cells = [c.strip() for c in line.strip().strip("│").split("│")]
        if len(cells) == len(header) and cells[0] != "key":
            rows[cells[0]] = dict(zip(header, cells, strict=True))
        elif cells and cells[0] == "key":
            break
    return rows


def test_without_a_launch_the_tools_say_so(teleo):
    for args in (("goal", "list"), ("goal", "post", "(x)"), ("inspect", "--once")):
        done = teleo(*args)
        assert done.returncode != 0
        assert "no running teleo launch found" in done.stderr


def test_goals_posted_while_running_reach_the_executive(teleo):
    # a parked car, whose law holds at every cycle: with hold_speed.toml the car stopped at
    # the city's edge (issue 31, N18), its speed law could no longer hold, and g2 waited on it
    launcher = teleo.start("launch", str(PARKED), "--cycles", "0",
                           "--summary", str(teleo.run_dir / "summary.json"))
    try:
        teleo.run_info()
        posted = teleo("goal", "post", "(package-delivered PACKET2)", "--priority", "2")
        assert posted.returncode == 0, posted.stderr
        assert "posted g2 for ME" in posted.stdout
        refused = teleo("goal", "post", "(flying ME)")
        assert refused.returncode != 0 and "undefined concept 'flying'" in refused.stderr
        arity = teleo("goal", "post", "(package-delivered A B)")
        assert "takes 1 argument(s), got 2" in arity.stderr
        # the executive reports on g2 once it has it: its status leaves "pending", and is
        # told as it is: this program has no skill for package-delivered, an impasse
        assert wait_for(lambda: goal_statuses(teleo).get("g2") == "impasse", 60)
        assert teleo("goal", "cancel", "g1").returncode == 0
        assert teleo("goal", "priority", "g2", "7").returncode == 0
        shown = teleo("inspect", "--seconds", "1", "--key", "agent/ME/intention")
        assert shown.returncode == 0, shown.stderr
        for text in ("ME.executive", "world/state", "agent/ME/actions", '"id": "g2"'):
            assert text in shown.stdout
        assert '"id": "g1"' not in shown.stdout.split("agent/ME/intention:")[1]
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    summary = json.loads((teleo.run_dir / "summary.json").read_text())
    goals = {g["id"]: (g["status"], g["priority"]) for g in summary["goals"]}
    assert goals["g1"] == ("cancelled", 3)
    # g2 is still pursued: in impasse, as the law holds throughout
    assert goals["g2"] == ("impasse", 7)


def test_a_killed_inference_is_restarted_and_no_goal_is_lost(teleo, tmp_path):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0",
                           "--summary", str(teleo.run_dir / "summary.json"))
    try:
        info = teleo.run_info()
        assert wait_for(lambda: trace_lines(info) >= 10, 60)
        killed = info["pids"]["ME.inference"]
        os.kill(killed, signal.SIGKILL)
        at_kill = trace_lines(info)
        assert wait_for(lambda: teleo.run_info()["pids"]["ME.inference"] != killed, 60), \
            teleo.launch_output()
        assert wait_for(lambda: trace_lines(info) >= at_kill + 50, 60)
        shown = teleo("inspect", "--seconds", "1")
        assert shown.returncode == 0, shown.stderr
        rows = process_rows(shown.stdout)
        assert rows["ME.inference"]["restarts"] == "1", shown.stdout   # the launcher's count
        assert rows["world"]["cycle"].isdigit() and rows["world"]["compute ms"] != "-"
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    assert "ME.inference exited with code -9: restarted (1)" in teleo.launch_output()
    summary = json.loads((teleo.run_dir / "summary.json").read_text())
    assert summary["completed"] and summary["restarts"] == {"ME.inference": 1}
    assert [(g["id"], g["goal"]) for g in summary["goals"]] == [
        ("g1", "(package-delivered PACKET1)")]
    assert summary["goals"][0]["status"] in PURSUED
    # lockstep: the world waited for the new inference, so the run is the same as one
    # where nothing was killed
    cycles = summary["cycles"]
    clean = Teleo(tmp_path / "clean")
    clean.run_dir.mkdir()
    done = clean("launch", str(HOLD_SPEED), "--cycles", str(cycles),
                 "--summary", str(clean.run_dir / "summary.json"))
    assert done.returncode == 0, done.stdout + done.stderr
    clean_trace = json.loads((clean.run_dir / "summary.json").read_text())["trace"]
    assert Path(summary["trace"]).read_text() == Path(clean_trace).read_text()


def test_a_killed_goal_entry_process_comes_back_with_every_goal(teleo):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0",
                           "--summary", str(teleo.run_dir / "summary.json"))
    try:
        info = teleo.run_info()
        assert teleo("goal", "post", "(package-delivered PACKET2)", "-p", "4").returncode == 0
        before = goal_statuses(teleo)
        assert set(before) == {"g1", "g2"}
        killed = info["pids"]["goals"]
        os.kill(killed, signal.SIGKILL)
        assert wait_for(lambda: teleo.run_info()["pids"]["goals"] != killed, 60), \
            teleo.launch_output()
        at_restart = trace_lines(info)
        assert wait_for(lambda: trace_lines(info) >= at_restart + 50, 60)  # the run goes on
        assert set(goal_statuses(teleo)) == {"g1", "g2"}
        posted = teleo("goal", "post", "(package-delivered PACKET3)")
        assert "posted g3" in posted.stdout  # ids go on from the saved store
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    summary = json.loads((teleo.run_dir / "summary.json").read_text())
    assert summary["restarts"] == {"goals": 1}
    assert [g["id"] for g in summary["goals"]] == ["g1", "g2", "g3"]


def test_with_two_agents_a_post_must_name_its_agent_and_a_cancel_finds_the_goals_owner(
        teleo, tmp_path):
    launcher = teleo.start("launch", two_cars(tmp_path, cycles=0), "--agents-per-process",
                           "2", "--no-record")
    try:
        teleo.run_info()
        unnamed = teleo("goal", "post", "(package-delivered PACKET2)", "-p", "4")
        assert unnamed.returncode == 1
        assert "has 2 agents (A1, A2): say which one the goal is for with --agent" in \
            unnamed.stderr
        assert "Traceback" not in unnamed.stderr
        posted = teleo("goal", "post", "(package-delivered PACKET2)", "-p", "4", "-a", "A2")
        assert posted.returncode == 0 and "posted g1 for A2" in posted.stdout, posted.stderr
        raised = teleo("goal", "priority", "g1", "6")   # no --agent: g1 is A2's
        assert raised.returncode == 0 and "g1 now has priority 6" in raised.stdout, \
            raised.stderr
        assert teleo("goal", "cancel", "g1").returncode == 0
        listed = json.loads(teleo("goal", "list", "--json").stdout)
        assert [(g["id"], g["agent"], g["status"], g["priority"]) for g in listed] == [
            ("g1", "A2", "cancelled", 6)]
        ghost = teleo("goal", "cancel", "g9")
        assert ghost.returncode == 1 and "has no goal 'g9'" in ghost.stderr
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
