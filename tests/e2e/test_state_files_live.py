"""An executive whose state file is not UTF-8 when it restarts (drills 2026-12-04 D1 and D4:
it crashed at every restart and the run ended FAILED; with a cut file it restarted but
rewrote learned-ME.tlp with 0 skills): the file is set aside and named in the summary, the
run goes on, and the learned skills on disk are kept."""

from __future__ import annotations

import os
import signal
from pathlib import Path

from e2e_helpers import ROOT
from fault_helpers import cycles, restarted, summary, wait_cycles


def _skills(path: Path) -> int:
    from agents.lang.solving.learned import clause_heads

    return len(clause_heads(path.read_text()))


def test_a_binary_state_file_is_set_aside_and_the_skills_on_disk_kept(teleo):
    launcher = teleo.start("launch", str(ROOT / "scenarios" / "blocks_figure3.toml"),
                           "--cycles", "0", "--summary", str(teleo.run_dir / "summary.json"))
    info = teleo.run_info()
    run_dir = Path(info["run_dir"])
    try:
        wait_cycles(info, 40)
        learned = run_dir / "learned-ME.tlp"
        before = _skills(learned)
        pid = info["pids"]["ME.executive"]
        os.kill(pid, signal.SIGSTOP)
        (run_dir / "state-ME.json").write_bytes(b"\xff\xfe\x00binary" * 10)
        os.kill(pid, signal.SIGKILL)
        restarted(info, "ME.executive")
        wait_cycles(info, cycles(info) + 30)
    finally:
        launcher.send_signal(signal.SIGINT)
        launcher.wait(120)
    s = summary(teleo)
    assert s["left_down"] == [] and not any("gave up" in f for f in s["failures"]), s
    assert s["set_aside"] == [str(run_dir / "state-ME.json.bad")]
    assert (run_dir / "state-ME.json.bad").read_bytes() == b"\xff\xfe\x00binary" * 10
    assert before >= 1 and _skills(learned) >= before
    assert f"SET ASIDE: {run_dir / 'state-ME.json.bad'}" in teleo.launch_output()
