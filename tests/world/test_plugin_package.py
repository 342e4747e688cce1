"""A world package of its own, installed by pip: examples/teleo-world-bins goes into a fresh
virtual environment beside teleo (teleo's dependencies come from this project's .venv through
a .pth file, so nothing is downloaded), and from an empty folder `teleo worlds` lists it,
`teleo check` passes its program and scenario, `teleo simulate` achieves its goals and
`teleo launch` runs it over the bus with the same trace. The commands of
docs/tutorial-world.md are run as the chapter writes them, and their output must contain the
lines it shows. Run it under `heavy` (it builds two packages and launches processes)."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "teleo-world-bins"
TUTORIAL = ROOT / "docs" / "tutorial-world.md"


@pytest.fixture(scope="module")
def venv(tmp_path_factory) -> Path:
    """A fresh venv (no pip of its own) with teleo and the example installed, not editable."""
    home = tmp_path_factory.mktemp("plugin")
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(home / "venv")],
                   check=True)
    python = home / "venv" / "bin" / "python"
    site = subprocess.run([str(python), "-c", "import sysconfig; "
                           "print(sysconfig.get_paths()['purelib'])"], check=True,
                          capture_output=True, text=True).stdout.strip()
    (Path(site) / "teleo-dev-deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    done = subprocess.run([str(python), "-m", "pip", "install", "-q", "--no-deps",
                           "--no-build-isolation", "--no-index", str(ROOT), str(EXAMPLE)],
                          env=_env(), capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    return home


def _env(run_dir: Path | None = None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
    env["PIP_DISABLE_PIP_VERSION_CHECK"] = "1"
    if run_dir is not None:
        env["TELEO_RUN_DIR"] = str(run_dir)
    return env


@pytest.fixture(scope="module")
def folder(venv) -> Path:
    """An empty folder holding only the example's program and scenario."""
    here = venv / "empty"
    here.mkdir()
    for name in ("bins.tlp", "sort.toml"):
        shutil.copy(EXAMPLE / name, here / name)
    return here


def _teleo(venv: Path, folder: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(venv / "venv" / "bin" / "teleo"), *args], cwd=folder,
                          env=_env(venv / "runs"), capture_output=True, text=True, timeout=300)


def test_the_installed_package_is_listed_with_its_distribution(venv, folder):
    done = _teleo(venv, folder, "worlds", "--json")
    assert done.returncode == 0, done.stderr
    worlds = {w["name"]: w for w in json.loads(done.stdout)["worlds"]}
    assert worlds["bins"] == {
        "name": "bins", "package": "teleo-world-bins", "version": "0.1.0",
        "target": "teleo_world_bins:DOMAIN", "error": "",
        "summary": "a robot sorts coloured balls into the bins of their colour (example plug-in)"}
    assert {"driving", "blocks", "office"} <= set(worlds)
    where = subprocess.run([str(venv / "venv" / "bin" / "python"), "-c",
                            "import world, teleo_world_bins as b; "
                            "print(world.__file__, b.__file__)"],
                           cwd=folder, env=_env(), capture_output=True, text=True)
    assert str(venv / "venv") in where.stdout and str(ROOT) not in where.stdout, where.stdout


def _tutorial_blocks() -> list[tuple[list[str], list[str]]]:
    """The chapter's shell blocks: (its `$ teleo ...` commands, the output lines shown)."""
    blocks, lines, inside = [], TUTORIAL.read_text().splitlines(), False
    for line in lines:
        if line.startswith("```"):
            inside = not inside
            if inside:
                blocks.append([])
            continue
        if inside:
            blocks[-1].append(line)
    out = []
    for block in blocks:
        if block and block[0].startswith("$ teleo "):
            out.append(([b[2:] for b in block if b.startswith("$ ")],
                        [b.strip() for b in block if b.strip() and not b.startswith("$ ")]))
    return out


def test_the_tutorial_commands_run_and_print_what_it_shows(venv, folder):
    blocks = _tutorial_blocks()
    ran = [c for commands, _ in blocks for c in commands]
    assert ran == ["teleo check bins.tlp sort.toml", "teleo worlds", "teleo simulate sort.toml",
                   "teleo launch sort.toml"]
    for commands, shown in blocks:
        for command in commands:
            done = _teleo(venv, folder, *command.split()[1:])
            assert done.returncode == 0, (command, done.stdout, done.stderr)
            printed = [line.strip() for line in done.stdout.splitlines()]
            missing = [line for line in shown if line not in printed]
            assert not missing, (command, missing, done.stdout)


def test_simulate_and_launch_give_the_same_trace_and_achieve_every_goal(venv, folder):
    sim = _teleo(venv, folder, "simulate", "sort.toml", "--trace", "sim.jsonl", "--json")
    assert sim.returncode == 0, sim.stderr
    summary = json.loads(sim.stdout)
    assert [g["status"] for g in summary["goals"]] == ["achieved"] * 3
    assert summary["achievements"] == {"ME": {"balls_sorted": 3}}
    launch = _teleo(venv, folder, "launch", "sort.toml", "--summary", "launch.json")
    assert launch.returncode == 0, launch.stdout + launch.stderr
    over_bus = json.loads((folder / "launch.json").read_text())
    assert over_bus["domain"] == "bins" and over_bus["completed"]
    assert [g["status"] for g in over_bus["goals"]] == ["achieved"] * 3
    assert Path(over_bus["trace"]).read_text() == (folder / "sim.jsonl").read_text()


def test_the_contract_test_runs_over_the_installed_world(venv):
    """tests/world/test_domain_contract.py is parametrised over every registered world: in
    this venv, the example's too."""
    done = subprocess.run([str(venv / "venv" / "bin" / "python"), "-m", "pytest", "-q",
                           "-p", "no:cacheprovider", "tests/world/test_domain_contract.py",
                           "-k", "bins"], cwd=ROOT, env=_env(), capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    passed = re.search(r"(\d+) passed", done.stdout)
    assert passed and int(passed.group(1)) >= 8 and "deselected" in done.stdout, done.stdout
