"""`teleo launch scenarios/blocks_figure3.toml`: seed 000's Figure 3 over the real processes
(world, perception, inference, executive, goal entry) on zenoh and pymunk, in lockstep; and
`teleo event` changing the Blocks World under a running agent."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from e2e_helpers import ROOT, Teleo, interrupt, wait_for

FIGURE3 = ROOT / "scenarios" / "blocks_figure3.toml"


@pytest.fixture(scope="module")
def figure3(tmp_path_factory):
    folder = tmp_path_factory.mktemp("blocks")
    done = Teleo(folder)("launch", str(FIGURE3), "--summary", str(folder / "summary.json"),
                         "--render", str(folder / "run.gif"))
    return folder, done


def _trace(summary: dict) -> list[dict]:
    return [json.loads(x) for x in Path(summary["trace"]).read_text().splitlines()]


def test_figure3_over_the_processes_achieves_clear_a(figure3):
    folder, done = figure3
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads((folder / "summary.json").read_text())
    assert summary["completed"] and summary["domain"] == "blocks" and summary["cycles"] == 8
    assert [(g["goal"], g["status"]) for g in summary["goals"]] == [("(clear A)", "achieved")]
    assert "goals achieved: 1 of 1" in done.stdout
    assert summary["law_violations"] == {"ME": {"blocks_dropped": 0}}
    assert summary["achievements"] == {"ME": {"blocks_moved": 1}}
    assert (folder / "run.gif").read_bytes()[:6] == b"GIF89a"


def test_figure3_trace_has_the_seeds_three_actions(figure3):
    folder, _ = figure3
    summary = json.loads((folder / "summary.json").read_text())
    acted = [line["actions"]["ME"] for line in _trace(summary) if line["actions"]["ME"]]
    assert acted == [[["*unstack", "C", "B"]], [["*putdown", "C", "T"]],
                     [["*unstack", "B", "A"]]]


def test_two_launches_of_figure3_give_the_same_trace(figure3, tmp_path):
    folder, _ = figure3
    again = Teleo(tmp_path)("launch", str(FIGURE3), "--summary", str(tmp_path / "summary.json"))
    assert again.returncode == 0, again.stdout + again.stderr
    first = json.loads((folder / "summary.json").read_text())["trace"]
    second = json.loads((tmp_path / "summary.json").read_text())["trace"]
    assert first != second and Path(first).read_text() == Path(second).read_text()


def _injected(info: dict) -> list[dict]:
    path = Path(info["run_dir"]) / "trace.jsonl"
    lines = [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []
    return [e for line in lines for e in line.get("events", [])]


def _actions(info: dict) -> list[list]:
    path = Path(info["run_dir"]) / "trace.jsonl"
    lines = [json.loads(x) for x in path.read_text().splitlines()] if path.exists() else []
    return [a for line in lines for a in line["actions"].get("ME", [])]


def test_a_block_added_on_a_by_teleo_event_is_cleared_again(teleo):
    """After Figure 3, a person puts D on A: the agent puts B down and unstacks D."""
    launcher = teleo.start("launch", str(FIGURE3), "--cycles", "0")
    try:
        info = teleo.run_info()
        assert wait_for(lambda: ["*unstack", "B", "A"] in _actions(info), 60), \
            teleo.launch_output()
        sent = teleo("event", '{"kind": "add", "block": "D", "on": "A"}')
        assert sent.returncode == 0, sent.stderr
        assert "applied at cycle" in sent.stdout
        bad = teleo("event", '{"kind": "quake"}')          # the world's verdict: refused
        assert bad.returncode == 1 and "unknown kind 'quake'" in bad.stderr, bad.stderr
        assert wait_for(lambda: ["*unstack", "D", "A"] in _actions(info), 60), \
            teleo.launch_output()
        assert wait_for(lambda: len(_injected(info)) == 2, 60), teleo.launch_output()
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    after = _actions(info)[_actions(info).index(["*unstack", "B", "A"]) + 1:]
    assert after[:2] == [["*putdown", "B", "T"], ["*unstack", "D", "A"]]
    outcomes = {e["event"]["kind"]: e for e in _injected(info)}
    assert outcomes["add"]["status"] == "done"
    assert outcomes["quake"]["status"] == "failed"
    assert "unknown kind 'quake'" in outcomes["quake"]["reason"]
