"""`teleo program load` swaps a running agent's program at a cycle boundary and reports the
stages' verdict; `teleo set` changes what may change while a launch runs (issue 34, item 2).
The same swap at the same cycle gives the same trace; the record and `teleo explain` show
the program each cycle ran."""

from __future__ import annotations

import json
import os
import signal
from pathlib import Path

from e2e_helpers import FIXTURES, HOLD_SPEED, Teleo, interrupt, wait_for

from tools.records.run_record import RunRecord, locate
from tools.view.feeds import load_file
from tools.view.model import ViewModel

SLOW = FIXTURES / "hold_slow.tlp"
AT, CYCLES = 300, "600"


def _trace(info: dict) -> list[dict]:
    return [json.loads(x) for x in (Path(info["run_dir"]) / "trace.jsonl").read_text()
            .splitlines()]


def _swapped_at(teleo: Teleo) -> dict:
    """A lockstep launch given hold_slow.tlp at cycle AT: held first, so AT is still ahead."""
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", CYCLES,
                           "--summary", str(teleo.run_dir / "summary.json"))
    try:
        info = teleo.run_info()
        held = teleo("pause", "--json", "--quiet")
        assert held.returncode == 0, held.stderr + teleo.launch_output()
        assert json.loads(held.stdout)["cycle"] < AT, "the run passed AT before it was held"
        load = teleo("program", "load", "ME", str(SLOW), "--at", str(AT), "--json", "--quiet")
        assert load.returncode == 0, load.stderr
        said = json.loads(load.stdout)
        assert said["state"] == "scheduled" and said["cycle"] == AT and said["paused"], said
        assert teleo("resume", "--quiet").returncode == 0
        assert launcher.wait(240) == 0, teleo.launch_output()
    finally:
        if launcher.poll() is None:
            interrupt(launcher)
    return info


def test_the_same_swap_at_the_same_cycle_gives_the_same_trace_and_the_record_shows_it(
        teleo, tmp_path):
    first = _swapped_at(teleo)
    again = Teleo(tmp_path / "again")
    again.run_dir.mkdir()
    second = _swapped_at(again)
    a, b = (Path(i["run_dir"]) / "trace.jsonl" for i in (first, second))
    assert a != b and a.read_bytes() == b.read_bytes()
    lines = _trace(first)
    assert len(lines) == int(CYCLES)
    control = [(x["cycle"], x["control"]) for x in lines if "control" in x]
    assert control == [(AT, {"programs": {"ME": {"name": str(SLOW),
                                                  "text": SLOW.read_text()}}})]
    # the record: the stages' verdicts at AT, and explain names the program of each cycle
    before = teleo("explain", first["run_dir"], "--cycle", str(AT - 1), "--json")
    after = teleo("explain", first["run_dir"], "--cycle", str(AT), "--json")
    assert before.returncode == 0 and after.returncode == 0, before.stderr + after.stderr
    was, now = json.loads(before.stdout), json.loads(after.stdout)
    assert was["program"] == {"name": str(FIXTURES / "hold_speed.tlp"), "since": 0}
    assert now["program"] == {"name": str(SLOW), "since": AT}, now["program"]
    assert [g["goal"] for g in now["decision"]["goals"]] == ["(at-slow-speed ME)"]
    assert now["swap"]["ok"] and now["swap"]["dropped"] == [
        "program goal p1 (at-desired-speed ME): not a goal of the new program",
        "goal g1 (package-delivered PACKET1): undefined concept 'package-delivered'"]
    text = teleo("explain", first["run_dir"], "--cycle", str(AT + 1))
    assert f"program {SLOW} (from cycle {AT})" in text.stdout.splitlines()[0], text.stdout
    health = [json.loads(x) for x in (Path(first["run_dir"]) / "health.jsonl").read_text()
              .splitlines()]
    assert [(h["cycle"], h["agent"], h["name"]) for h in health if h["kind"] == "program"] \
        == [(AT, "ME", str(SLOW))]
    # the view of the record (as of its replay) explains each cycle with the program it ran
    model = ViewModel(None, 5000)
    load_file(model, locate(first["run_dir"]))
    assert model.programs.get("ME", AT)[1] == f"{SLOW} (from cycle {AT})"
    assert model.programs.get("ME", AT - 1)[1] == str(FIXTURES / "hold_speed.tlp")
    replayed = teleo("replay", first["run_dir"], "--rate", "0", "--wait", "0",
                     timeout=120)
    assert f"cycle {AT}: ME runs {SLOW} from here on" in replayed.stderr, replayed.stderr


def test_a_live_swap_reports_the_stages_verdict_and_a_bad_file_leaves_the_program(teleo,
                                                                                tmp_path):
    nothing = teleo("program", "load", "ME", str(SLOW))
    assert nothing.returncode == 1 and nothing.stderr.startswith(
        "Error: no running teleo launch found"), nothing.stderr
    bad = tmp_path / "bad.tlp"
    bad.write_text("((fast ?x)\n :percepts ((self ?x speed ?s))\n :tests ((> ?s ?nope))))\n")
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        refused = teleo("program", "load", "ME", str(bad), "--quiet")
        assert refused.returncode == 1, refused.stdout
        errors = refused.stderr.splitlines()
        assert errors[0].startswith(f"{bad}:") and errors[0].split(":")[1].isdigit(), errors
        assert errors[-1] == f"Error: {bad}: not loaded: the running program is untouched"
        past = teleo("program", "load", "ME", str(SLOW), "--at", "0", "--quiet")
        assert past.returncode == 1 and past.stderr.startswith(
            f"Error: run {info['run']}: the world refused: control: load: at: expected a "
            "cycle >= "), past.stderr
        nobody = teleo("program", "load", "YOU", str(SLOW), "--quiet")
        assert nobody.stderr == f"Error: run {info['run']} has no agent 'YOU'; agents: ME\n"
        load = teleo("program", "load", "ME", str(SLOW), "--quiet")
        assert load.returncode == 0, load.stderr + teleo.launch_output()
        head, *dropped = load.stdout.splitlines()
        assert head.startswith(f"run {info['run']}: ME runs {SLOW} from cycle ")
        assert head.endswith(" (inference and executive); dropped:"), head
        k = int(head.split(" from cycle ")[1].split()[0])
        assert dropped == [
            "  program goal p1 (at-desired-speed ME): not a goal of the new program",
            "  goal g1 (package-delivered PACKET1): undefined concept 'package-delivered'"]
        # goals are checked against the program the agent runs now
        taken = teleo("goal", "post", "(crawling ME)", "--priority", "5", "--quiet")
        assert taken.returncode == 0, taken.stderr
        gone = teleo("goal", "post", "(package-delivered PACKET2)", "--priority", "5",
                     "--quiet")
        assert gone.returncode == 1 and "undefined concept 'package-delivered'" in gone.stderr
        # the verdict is the stages' own: their outputs of cycle k say it
        again = teleo("program", "load", "ME", str(SLOW), "--json", "--quiet")
        verdict = json.loads(again.stdout)
        assert verdict["state"] == "swapped" and verdict["cycle"] > k, verdict
        assert verdict["stages"]["inference"] == {"program": str(SLOW), "ok": True,
                                                  "reason": "", "dropped": []}
        assert verdict["dropped"] == []   # the same program: everything carried over
        shown = teleo("set", "run.render_every=20", "--json", "--quiet")
        assert shown.returncode == 0, shown.stderr
        assert json.loads(shown.stdout)["value"] == 20
        fixed = teleo("set", "world.pedestrians=5", "--quiet")
        assert fixed.returncode == 1 and fixed.stderr.startswith(
            "Error: world.pedestrians cannot change while the run runs"), fixed.stderr
        wrong = teleo("set", "run.deadline=-1", "--quiet")
        assert wrong.returncode == 1 and len(wrong.stderr.splitlines()) == 1
        assert "[run].deadline: expected > 0" in wrong.stderr, wrong.stderr
        back = teleo("set", "agents.ME.program=" + str(FIXTURES / "hold_speed.tlp"), "--quiet")
        assert back.returncode == 0 and " runs " in back.stdout, back.stderr
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    out = teleo.launch_output()
    assert "exited with code" not in out and "restarted" not in out, out
    lines = _trace(info)
    swaps = [x["control"] for x in lines if "control" in x]
    assert [sorted(c) for c in swaps] == [["programs"], ["programs"], ["set"], ["programs"]]
    assert swaps[2] == {"set": [{"key": "run.render_every", "value": 20}]}
    assert lines[k]["control"]["programs"]["ME"]["name"] == str(SLOW)


def test_a_stage_restarted_after_a_swap_runs_the_program_swapped_in(teleo):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        load = teleo("program", "load", "ME", str(SLOW), "--json", "--quiet")
        assert load.returncode == 0, load.stderr + teleo.launch_output()
        k = json.loads(load.stdout)["cycle"]
        for stage in ("ME.inference", "ME.executive"):
            os.kill(teleo.run_info()["pids"][stage], signal.SIGKILL)
            assert wait_for(lambda s=stage: teleo.run_info()["restarts"].get(s) == 1, 60), \
                teleo.launch_output()
        again = teleo("program", "load", "ME", str(SLOW), "--json", "--quiet")  # all up again
        assert again.returncode == 0, again.stderr + teleo.launch_output()
        held = teleo("pause", "--json", "--quiet")
        c = json.loads(held.stdout)["cycle"]
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    logs = Path(info["run_dir"]) / "logs"
    for stage in ("ME.inference", "ME.executive"):
        text = next(logs.glob(f"{stage}*")).read_text()
        assert f"running {SLOW}, swapped in at cycle {k}" in text, text[-2000:]
    last = json.loads(teleo("explain", info["run_dir"], "--cycle", str(c - 1), "--json").stdout)
    assert [g["goal"] for g in last["decision"]["goals"]] == ["(at-slow-speed ME)"]
    beliefs = RunRecord(locate(info["run_dir"])).by_cycle("beliefs", "ME")[c - 1]["beliefs"]
    assert beliefs and {b[0] for b in beliefs} <= {"at-slow-speed", "crawling", "too-fast"}
