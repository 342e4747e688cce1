"""`teleo simulate` keeps user goals as a launch does (issue 12, items 7 and 11): ids g1, g2,
... from the goal store, statuses and notes mirrored from each decision (with the hint for an
object no percept mentions), scripted cancels and the summary JSON a launch prints."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from tools.cli import cli

ROOT = Path(__file__).resolve().parents[2]
DRIVING = ROOT / "programs" / "driving.tlp"


def scenario(tmp_path: Path, goals: str) -> Path:
    text = (ROOT / "scenarios" / "driving_demo.toml").read_text()
    text = text[:text.index("[[goals]]")].replace('"programs/driving.tlp"', f'"{DRIVING}"')
    path = tmp_path / "s.toml"
    path.write_text(text + goals)
    return path


def test_goal_ids_statuses_notes_and_a_scripted_cancel(tmp_path):
    path = scenario(tmp_path, """
[[goals]]
goal = "(package-delivered PACKET9)"
priority = 6
[[goals]]
goal = "(package-delivered PACKET1)"
priority = 5
at_cycle = 2
[[goals]]
op = "cancel"
goal_id = "g2"
at_cycle = 4
""")
    result = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "6", "--json"])
    assert result.exit_code == 0, result.output
    summary = json.loads(result.stdout)
    got = {g["id"]: g for g in summary["goals"]}
    assert [(g["id"], g["goal"], g["posted_cycle"]) for g in summary["goals"]] == [
        ("g1", "(package-delivered PACKET9)", 0), ("g2", "(package-delivered PACKET1)", 2)]
    assert got["g1"]["status"] in ("pending", "impasse", "failed")
    assert "no percept mentions PACKET9: is there such an object?" in got["g1"]["note"]
    assert (got["g2"]["status"], got["g2"]["updated_cycle"]) == ("cancelled", 4)
    assert (summary["mode"], summary["cycles"], summary["completed"]) == ("simulate", 6, True)
    assert summary["goals_achieved"] == 0 and summary["counters"]["ME"]["deliveries"] == 0
