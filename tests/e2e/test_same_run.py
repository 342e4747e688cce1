"""`teleo simulate` and `teleo launch` of one scenario are the same run told the same way
(issue 12, item 11): the same trace lines, goal ids and summary; `--json` summaries on stdout;
a progress bar on a terminal and nothing when not a terminal (item 14)."""

from __future__ import annotations

import json
import os
import pty
import select
import subprocess

from e2e_helpers import HOLD_SPEED, ROOT, TELEO


def test_simulate_and_a_lockstep_launch_give_the_same_trace_goal_ids_and_summary(teleo,
                                                                                 tmp_path):
    launched = teleo("launch", str(HOLD_SPEED), "--json", timeout=300)
    assert launched.returncode == 0, launched.stderr
    summary = json.loads(launched.stdout)                 # stdout holds the JSON and nothing else
    assert "processes and a router at" in launched.stderr  # the launch's lines went to stderr
    simulated = teleo("simulate", str(HOLD_SPEED), "--json", "--trace",
                      str(tmp_path / "sim.jsonl"), timeout=300)
    assert simulated.returncode == 0, simulated.stderr
    again = json.loads(simulated.stdout)
    trace = (tmp_path / "sim.jsonl").read_text()
    assert trace == open(summary["trace"]).read()
    assert len(trace.splitlines()) == 30 and '"events": [{"event": {"ahead_of": "ME"' in trace
    keys = ("id", "agent", "goal", "priority", "status", "posted_cycle")
    assert [{k: g[k] for k in keys} for g in again["goals"]] == \
           [{k: g[k] for k in keys} for g in summary["goals"]]
    assert [g["id"] for g in again["goals"]] == ["g1"]
    assert set(summary) <= set(again) | {"learned"}
    for key in ("cycles", "completed", "goals_achieved", "counters", "law_violations", "seed"):
        assert again[key] == summary[key], key
    assert (summary["mode"], again["mode"]) == ("lockstep", "simulate")


def _on_a_terminal(*args: str, run_dir=None, timeout: float = 300) -> tuple[int, str]:
    """Run `teleo ARGS` with stderr on a pseudo-terminal; returns (exit code, what it wrote
    there)."""
    master, slave = pty.openpty()
    env = {**os.environ, "COLUMNS": "120", "TERM": "xterm",
           **({"TELEO_RUN_DIR": str(run_dir)} if run_dir else {})}
    proc = subprocess.Popen([*TELEO, *args], cwd=ROOT, env=env, stdout=subprocess.DEVNULL,
                            stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    seen = b""
    while True:
        ready, _, _ = select.select([master], [], [], 1.0)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:
                break
            if not chunk:
                break
            seen += chunk
        elif proc.poll() is not None:
            break
    os.close(master)
    return proc.wait(timeout), seen.decode(errors="replace")


def test_a_progress_bar_with_cycles_per_second_on_a_terminal_only(teleo):
    code, shown = _on_a_terminal("simulate", str(ROOT / "scenarios" / "driving_demo.toml"),
                                 "--cycles", "120")
    assert code == 0, shown
    assert "cycles/s" in shown and "/120" in shown
    plain = teleo("simulate", str(ROOT / "scenarios" / "driving_demo.toml"), "--cycles", "120",
                  timeout=300)
    assert plain.returncode == 0, plain.stderr
    assert "cycles/s" not in plain.stderr and "\x1b" not in plain.stderr   # nothing in a pipe
    code, shown = _on_a_terminal("launch", str(HOLD_SPEED), "--cycles", "200",
                                 run_dir=teleo.run_dir)
    assert code == 0, shown
    assert "cycles/s" in shown and "/200" in shown and "run hold-speed-" in shown
