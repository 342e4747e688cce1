"""bench/ipc/downward_layout.py: Fast Downward's benchmark folders (a domain.pddl, or a domain
file per problem) laid out as bench/ipc/ipc.py's --suites reads them."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from bench.ipc.downward_layout import lay_out
from bench.ipc.ipc import domain_file, suite_names

ROOT = Path(__file__).resolve().parents[2]


def test_both_layouts_become_tasks_with_their_domains(tmp_path):
    src = tmp_path / "src"
    (src / "shared").mkdir(parents=True)
    (src / "shared" / "domain.pddl").write_text("(define (domain shared))")
    for name in ("p02.pddl", "p01.pddl", "p03.pddl"):
        (src / "shared" / name).write_text(f"; {name}")
    (src / "own").mkdir()
    for k in (1, 2):
        (src / "own" / f"p0{k}.pddl").write_text(f"; problem {k}")
        (src / "own" / f"domain_p0{k}.pddl").write_text(f"; domain {k}")
    out = tmp_path / "out"
    assert lay_out(src, out, "shared", 2) == 2
    assert lay_out(src, out, "own", 5) == 2
    assert (out / "shared" / "task01.pddl").read_text() == "; p01.pddl"
    assert (out / "own" / "domain02.pddl").read_text() == "; domain 2"
    assert suite_names(out) == ["own", "shared"]
    assert domain_file(out, "own", 2) == out / "own" / "domain02.pddl"
    assert domain_file(out, "shared", 1) == out / "shared" / "domain.pddl"


def test_an_unknown_domain_is_one_usage_error(tmp_path):
    done = subprocess.run([sys.executable, "bench/ipc/downward_layout.py", str(tmp_path),
                           str(tmp_path / "out"), "--domains", "nowhere"], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and "--domains: nowhere: no such folder" in done.stderr
    assert "Traceback" not in done.stderr
