"""bench/ipc/agenda_cost.py in a real subprocess: it times the agenda by index against the
pairwise reference on a visitall grid it writes, both in one run, and says they agree; bad
arguments get one line."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

from tests.bench.scripts import run_script

ROOT = Path(__file__).resolve().parents[2]
BENCH = ROOT / "bench" / "ipc" / "agenda_cost.py"


def bench(*args: str) -> subprocess.CompletedProcess:
    return run_script(BENCH, *args, timeout=240)


def test_a_grid_is_ordered_alike_by_both_and_the_ratio_printed():
    done = bench("--grid", "5", "--repeat", "1")
    assert done.returncode == 0, done.stderr
    row = done.stdout.splitlines()[-1]
    m = re.search(r"grid\.pddl\s+(\d+)\s+[\d.]+s\s+[\d.]+s\s+[\d.]+x\s+yes$", row)
    assert m, row
    assert int(m.group(1)) == 24   # every cell but the robot's


def test_help_and_an_odd_number_of_files():
    assert "DOMAIN PROBLEM pairs" in " ".join(bench("--help").stdout.split())
    done = bench(str(BENCH))
    assert done.returncode == 2 and "an odd number was given" in done.stderr
