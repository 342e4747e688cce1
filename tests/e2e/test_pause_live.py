"""`teleo pause`, `teleo step-run N`, `teleo resume` hold a live lockstep launch between
cycles and report the world's verdict (issue 34, item 1); the trace of a paused and stepped
run is byte for byte the trace of the same run never paused, and nothing of the run takes
the hold for a stall or a dead stage."""

from __future__ import annotations

import json
import time
from pathlib import Path

from e2e_helpers import HOLD_SPEED, Teleo, interrupt, trace_lines

CYCLES = "400"


def _health(info: dict) -> list[dict]:
    path = Path(info["run_dir"]) / "health.jsonl"
    return [json.loads(x) for x in path.read_text().splitlines()]


def test_a_paused_and_stepped_launch_gives_the_trace_of_one_never_paused(teleo, tmp_path):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", CYCLES,
                           "--summary", str(teleo.run_dir / "summary.json"))
    try:
        info = teleo.run_info()
        held = teleo("pause", "--json")
        assert held.returncode == 0, held.stderr + teleo.launch_output()
        at = json.loads(held.stdout)
        k = at["cycle"]
        assert at["op"] == "pause" and at["paused"] and at["note"] == "", at
        assert k < int(CYCLES), "the run ended before it could be paused"
        assert trace_lines(info) == k       # cycles before k are recorded, k has not begun
        time.sleep(2.5)                     # longer than a stall is reported (1 s)
        assert trace_lines(info) == k       # held: no cycle ran meanwhile
        again = teleo("pause")
        assert again.stdout == f"run {info['run']}: paused at cycle {k} (already paused)\n"
        stepped = teleo("step-run", "3")
        assert stepped.returncode == 0, stepped.stderr
        assert stepped.stdout == f"run {info['run']}: paused at cycle {k + 3} after 3 cycles\n"
        assert trace_lines(info) == k + 3
        one = teleo("step-run", "--json")
        assert json.loads(one.stdout)["cycle"] == k + 4 and json.loads(one.stdout)["stepped"] == 1
        going = teleo("resume")
        assert going.returncode == 0, going.stderr
        assert going.stdout == f"run {info['run']}: running at cycle {k + 4}\n"
        assert launcher.wait(240) == 0, teleo.launch_output()
    finally:
        if launcher.poll() is None:
            interrupt(launcher)
    out = teleo.launch_output()
    assert "exited with code" not in out and "restarted" not in out, out
    health = _health(info)
    assert [(h["kind"], h["cycle"]) for h in health if h["kind"] in ("paused", "resumed")] == [
        ("paused", k), ("resumed", k), ("paused", k + 3), ("resumed", k + 3),
        ("paused", k + 4), ("resumed", k + 4)]
    # the hold is no stall: no cycle waited for a stage, none was given the safe action
    assert not [h for h in health if h["kind"] == "cycle" and (h.get("stalled") or h.get("noop"))]
    plain = Teleo(tmp_path / "plain")
    plain.run_dir.mkdir()
    done = plain("launch", str(HOLD_SPEED), "--cycles", CYCLES,
                 "--summary", str(plain.run_dir / "summary.json"), timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    paused = json.loads((teleo.run_dir / "summary.json").read_text())["trace"]
    never = json.loads((plain.run_dir / "summary.json").read_text())["trace"]
    assert paused != never
    assert Path(paused).read_bytes() == Path(never).read_bytes()
    assert trace_lines(info) == int(CYCLES)
    # the launch's record holds every cycle of it, held or not (`teleo record info`, item 3)
    summary = teleo("record", "info", info["run_dir"], "--json")
    assert summary.returncode == 0, summary.stderr
    held = json.loads(summary.stdout)
    assert held["cycles"]["states_held"] == [[0, int(CYCLES) - 1]] and held["agents"] == ["ME"]
    states = [c["count"] for c in held["channels"] if c["key"].endswith("/world/state")]
    assert len(states) == 1 and states[0] >= int(CYCLES)   # a state re-sent is recorded again


def test_a_realtime_launch_refuses_to_pause_and_nothing_running_is_said(teleo):
    nothing = teleo("pause")
    assert nothing.returncode == 1 and nothing.stderr.startswith("Error: no running teleo "
                                                                 "launch found"), nothing.stderr
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0", "--mode", "realtime")
    try:
        info = teleo.run_info()
        for args in (("pause",), ("step-run", "2"), ("resume",)):
            refused = teleo(*args, "--quiet")
            assert refused.returncode == 1, refused.stdout
            assert refused.stderr.startswith(
                f"Error: run {info['run']}: the world refused: pause and step hold a lockstep "
                "run between cycles; this run is realtime"), refused.stderr
            assert len(refused.stderr.splitlines()) == 1, refused.stderr
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()


def test_a_held_launch_stops_at_ctrl_c_where_it_was_held(teleo):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        held = teleo("pause", "--json", "--quiet")
        assert held.returncode == 0, held.stderr + teleo.launch_output()
        k = json.loads(held.stdout)["cycle"]
    finally:
        status = interrupt(launcher)
    assert status == 0, teleo.launch_output()
    final = json.loads((Path(info["run_dir"]) / "world-final.json").read_text())
    assert final["reason"].startswith("stopped by a signal"), final
    assert trace_lines(info) == k        # no cycle ran after the hold
    assert ("paused", k) in [(h["kind"], h.get("cycle")) for h in _health(info)]
