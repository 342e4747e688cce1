"""A launch never writes into an earlier run's folder (drills 2026-12-04 D3: `teleo launch
--run r1` twice overwrote the first run's trace and record, and its executive replayed the old
state): a `--run` id whose folder exists is refused in one line before anything starts, and
a launch that stops before starting leaves no folder behind."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from tools.cli import cli
from tools.launching.run_plan import claim_run_dir

ROOT = Path(__file__).resolve().parents[2]
DEMO = str(ROOT / "scenarios" / "driving_demo.toml")


def test_a_run_id_whose_folder_holds_an_earlier_run_is_refused(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    earlier = tmp_path / "runs" / "r1"
    earlier.mkdir(parents=True)
    (earlier / "trace.jsonl").write_text('{"cycle": 0}\n')
    result = CliRunner().invoke(cli, ["launch", DEMO, "--run", "r1", "--cycles", "5"])
    assert result.exit_code == 1
    assert result.output.strip().splitlines() == [
        f"Error: --run r1: the folder {earlier} holds an earlier run, and a launch never "
        "writes into one; give another id, or move that folder away first"]
    assert sorted(p.name for p in earlier.iterdir()) == ["trace.jsonl"]
    assert (earlier / "trace.jsonl").read_text() == '{"cycle": 0}\n'


def test_a_launch_refused_after_taking_its_folder_leaves_none(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path))
    result = CliRunner().invoke(cli, ["launch", DEMO, "--run", "r2", "--only", "world",
                                      "--agents-per-process", "2"])
    assert result.exit_code == 1 and "--agents-per-process" in result.output
    assert not (tmp_path / "runs" / "r2").exists()


def test_a_generated_id_that_is_taken_is_drawn_again(tmp_path):
    taken = tmp_path / "demo-abc123"
    taken.mkdir()
    run, folder = claim_run_dir("demo-abc123", taken, False, "demo", False)
    assert run != "demo-abc123" and run.startswith("demo-") and folder == tmp_path / run
    assert folder.is_dir() and not any(taken.iterdir())
