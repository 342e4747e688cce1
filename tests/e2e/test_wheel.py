"""A wheel of teleo, installed into a fresh venv, runs the shipped examples from an empty
folder (issue 33): the examples are package data (setup.py), `teleo examples` copies them,
and a shipped scenario runs by its name alone.

The wheel is built from a copy of the source (so the checkout gets no build/ folder) with
`pip wheel --no-deps --no-build-isolation`; the fresh venv has no pip of its own (the
project's pip installs into it with --python) and reaches the dependencies through a .pth
file naming this venv's site-packages, so nothing is downloaded. The only teleo it can import
is the wheel's: the checkout is not on its path, and its commands run from an empty folder."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SKIP = shutil.ignore_patterns(".venv", ".git", "out", "build", "*.egg-info", "__pycache__",
                              ".pytest_cache", ".ruff_cache", ".hypothesis", "tests", "bench")


def _run(args: list[str], cwd: Path, env: dict[str, str], timeout: float = 240
         ) -> subprocess.CompletedProcess:
    done = subprocess.run(args, cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)
    assert done.returncode == 0, f"{' '.join(args)}:\n{done.stdout}\n{done.stderr}"
    return done


def _installed(tmp: Path) -> Path:
    """A fresh venv with the wheel built from a copy of the source; its bin folder."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    source = tmp / "source"
    shutil.copytree(ROOT, source, ignore=SKIP)
    wheels = tmp / "wheels"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
          "-w", str(wheels), str(source)], tmp, env)
    wheel = next(wheels.glob("teleo-*.whl"))
    venv = tmp / "venv"
    _run([sys.executable, "-m", "venv", "--without-pip", str(venv)], tmp, env)
    python = venv / "bin" / "python"
    purelib = Path(_run([str(python), "-c", "import sysconfig; "
                         "print(sysconfig.get_paths()['purelib'])"], tmp, env).stdout.strip())
    (purelib / "project_deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    _run([sys.executable, "-m", "pip", "--python", str(python), "install", "--no-deps", "-q",
          str(wheel)], tmp, env)
    return venv / "bin"


def test_the_wheel_runs_the_shipped_examples_from_an_empty_folder(tmp_path):
    bin_dir = _installed(tmp_path)
    teleo = str(bin_dir / "teleo")
    empty = tmp_path / "empty"
    empty.mkdir()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["TELEO_RUN_DIR"] = str(tmp_path / "runs")

    where = _run([str(bin_dir / "python"), "-c", "import tools, teleo_examples; "
                  "print(tools.__file__); print(teleo_examples.__file__)"], empty, env)
    assert str(ROOT) not in where.stdout and str(tmp_path / "venv") in where.stdout

    copied = json.loads(_run([teleo, "examples", "ex", "--json"], empty, env).stdout)
    names = set(copied["files"])
    assert {"programs/blocks.tlp", "programs/laws/giving_way.tlp",
            "scenarios/blocks_figure3.toml", "scenarios/driving_demo.toml",
            "tutorial/cruise.tlp", "tutorial/cruise.toml"} <= names
    assert (empty / "ex" / "scenarios" / "blocks_figure3.toml").read_bytes() == \
        (ROOT / "scenarios" / "blocks_figure3.toml").read_bytes()
    again = subprocess.run([teleo, "examples", "ex"], cwd=empty, env=env, capture_output=True,
                           text=True, timeout=60)
    assert again.returncode != 0 and "--force" in again.stderr
    assert len(again.stderr.strip().splitlines()) == 1

    checked = _run([teleo, "check", "ex/scenarios/blocks_figure3.toml",
                    "ex/tutorial/cruise.toml", "driving_demo"], empty, env)
    assert checked.stdout.count(": ok (scenario") == 3, checked.stdout

    simulated = _run([teleo, "simulate", "blocks_figure3", "--no-record", "--json"], empty, env)
    summary = json.loads(simulated.stdout)
    assert summary["scenario"].startswith(str(tmp_path / "venv"))
    assert [(g["id"], g["status"]) for g in summary["goals"]] == [("g1", "achieved")]

    unknown = subprocess.run([teleo, "simulate", "blocks_figur"], cwd=empty, env=env,
                             capture_output=True, text=True, timeout=60)
    assert unknown.returncode != 0 and "blocks_figure3" in unknown.stderr
    assert len(unknown.stderr.strip().splitlines()) == 1

    launched = _run([teleo, "launch", "blocks_figure3", "--cycles", "4", "--no-record",
                     "--json"], empty, env)
    run = json.loads(launched.stdout)
    assert run["completed"] and run["cycles"] == 4, run
    assert [g["id"] for g in run["goals"]] == ["g1"]
    assert sorted(p.name for p in empty.iterdir()) == ["ex"]
