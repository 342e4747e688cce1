"""examples/bus_client.py, a client written from docs/bus.md with zenoh and msgpack alone,
speaks to a live launch (issue 33): it lists the run's processes and keys, follows the
agent's intention, posts a goal and reads its verdict, one achieved and one refused by the
engine's reasoning (failed, with the reason)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

from e2e_helpers import ROOT, interrupt

CLIENT = ROOT / "examples" / "bus_client.py"
STDLIB = set(sys.stdlib_module_names)


def test_the_client_imports_only_zenoh_msgpack_and_the_standard_library():
    tree = ast.parse(CLIENT.read_text())
    names = {a.name.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.Import)
             for a in n.names}
    names |= {n.module.split(".")[0] for n in ast.walk(tree)
              if isinstance(n, ast.ImportFrom) and n.module}
    assert names - STDLIB == {"zenoh", "msgpack"}


def client(run_file: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(CLIENT), "--run-file", str(run_file), *args],
                          cwd="/", capture_output=True, text=True, timeout=120)


def test_the_client_lists_follows_posts_and_reads_the_verdict(teleo):
    teleo.start("launch", "blocks_figure3", "--cycles", "0", "--mode", "realtime",
                "--no-record")
    try:
        info = teleo.run_info()
        run_file = teleo.run_files()[0]
        run = info["run"]
        listed = client(run_file, "keys", "--seconds", "3")
        assert listed.returncode == 0, listed.stderr
        lines = set(listed.stdout.splitlines())
        assert {"process world", "process goals", "process ME.perception",
                "process ME.inference", "process ME.executive"} <= lines
        assert {f"key teleo/{run}/world/state WorldState",
                f"key teleo/{run}/agent/ME/percepts Percepts",
                f"key teleo/{run}/agent/ME/intention Intention",
                f"key teleo/{run}/agent/ME/goal-list GoalList"} <= lines, lines

        followed = client(run_file, "follow", "ME", "--cycles", "3")
        assert followed.returncode == 0, followed.stderr
        cycles = [int(line.split(" cycle ")[1].split(":")[0])
                  for line in followed.stdout.splitlines()]
        assert len(cycles) == 3 and cycles == sorted(set(cycles)), followed.stdout
        assert "g1 (clear A)" in followed.stdout

        posted = client(run_file, "post", "ME", "(ontable B T)")
        assert posted.returncode == 0, posted.stderr
        said = posted.stdout.splitlines()
        assert said[0].startswith("posted: posted g2 for ME: (ontable B T)")
        assert said[1].startswith("verdict g2 achieved at cycle ")

        undoing = client(run_file, "post", "ME", "(on C A)")
        assert undoing.returncode == 0, undoing.stderr
        assert "verdict g3 failed at cycle " in undoing.stdout
        assert "without undoing g1 (clear A)" in undoing.stdout

        refused = client(run_file, "post", "ME", "(flying A)")
        assert refused.returncode == 1
        assert refused.stderr.startswith("bus_client: goal refused: ")
    finally:
        status = interrupt(teleo.launcher)
    summary = teleo.launch_output()
    assert "g2 ME (ontable B T) p5: achieved" in summary
    assert "g3 ME (on C A) p5: failed" in summary
    assert status == 1, summary   # a failed goal makes the run failed (docs/faults.md)
