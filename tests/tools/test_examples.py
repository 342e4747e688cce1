"""`teleo examples DEST` and the shipped scenarios by name (issue 33), in a checkout: the
files copied are the repository's, the tutorial's named blocks become files, nothing is
overwritten without --force, and a name that is no file finds the shipped scenario."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from tools.commands.examples import tutorial_files

ROOT = Path(__file__).resolve().parents[2]
TELEO = str(Path(sys.executable).parent / "teleo")


def teleo(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([TELEO, *args], cwd=cwd, capture_output=True, text=True, timeout=120)


def test_examples_copies_programs_scenarios_and_the_tutorials_files(tmp_path):
    done = teleo("examples", "ex", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    ex = tmp_path / "ex"
    for name in ("programs/driving.tlp", "programs/tables/original_1law.tlp",
                 "scenarios/office_figure6.toml"):
        assert (ex / name).read_bytes() == (ROOT / name).read_bytes()
    shipped = {p.name for p in (ROOT / "scenarios").glob("*.toml")}
    assert {p.name for p in (ex / "scenarios").iterdir()} == shipped
    tutorial = tutorial_files((ROOT / "docs" / "tutorial.md").read_text())
    assert {p.name for p in (ex / "tutorial").iterdir()} == set(tutorial)
    assert (ex / "tutorial" / "cruise.tlp").read_text() == tutorial["cruise.tlp"]
    assert "program = \"cruise.tlp\"" in tutorial["cruise.toml"]


def test_examples_refuses_to_overwrite_without_force(tmp_path):
    (tmp_path / "ex" / "scenarios").mkdir(parents=True)
    mine = tmp_path / "ex" / "scenarios" / "two_cars.toml"
    mine.write_text("# mine\n")
    refused = teleo("examples", "ex", cwd=tmp_path)
    assert refused.returncode == 1
    assert refused.stderr.strip().splitlines() == [
        "Error: teleo examples: ex/scenarios/two_cars.toml exists: give --force to "
        "overwrite, or another DEST"]
    assert mine.read_text() == "# mine\n" and not (tmp_path / "ex" / "programs").exists()
    forced = teleo("examples", "ex", "--force", "--json", cwd=tmp_path)
    assert forced.returncode == 0, forced.stderr
    assert json.loads(forced.stdout)["overwritten"] == ["scenarios/two_cars.toml"]
    assert mine.read_bytes() == (ROOT / "scenarios" / "two_cars.toml").read_bytes()


def test_a_shipped_scenario_is_found_by_its_name_and_an_unknown_one_gets_near_names(tmp_path):
    checked = teleo("check", "blocks_figure3", "office_figure6.toml", cwd=tmp_path)
    assert checked.returncode == 0, checked.stderr
    assert checked.stdout.count(": ok (scenario") == 2
    unknown = teleo("simulate", "office_figure", cwd=tmp_path)
    assert unknown.returncode != 0
    lines = unknown.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert "near: office_figure7, office_figure6, office_figure5" in lines[0]
    # a file of that name wins over the shipped scenario
    (tmp_path / "blocks_figure3").write_text("[run]\nnonsense = 1\n")
    local = teleo("check", "blocks_figure3", cwd=tmp_path)
    assert local.returncode == 1 and "nonsense" in local.stderr
