"""Deliveries through the real processes: PACKET1 is a goal from the start, PACKET2 is posted
mid-run with the real `teleo goal post`, as a user would; both get delivered and no
pedestrian is hit. First with the tests' own small program (deliver_ahead.tlp), then the
README's demo: scenarios/driving_demo.toml with programs/driving.tlp, run until both are
delivered, less its scripted PACKET2 request, which the test makes instead.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from e2e_helpers import FIXTURES, ROOT, interrupt, trace_lines, wait_for

BOTH = ("(package-delivered PACKET1)", "(package-delivered PACKET2)")


def statuses(teleo) -> dict[str, str]:
    """goal text -> status, from `teleo goal list`."""
    listed = teleo("goal", "list")
    rows = (line.split(maxsplit=4) for line in listed.stdout.splitlines()[1:])
    return {row[4]: row[3] for row in rows if len(row) == 5}


def deliver_two(teleo, scenario: Path, post_after: int, timeout: float) -> dict:
    """Launch `scenario` (it must run until stopped), post PACKET2 after `post_after` cycles,
    wait until both packages are achieved, Ctrl-C; returns the summary."""
    summary_file = teleo.run_dir / "summary.json"
    launcher = teleo.start("launch", str(scenario), "--cycles", "0", "--summary",
                           str(summary_file), "--render", str(teleo.run_dir / "run.png"))
    try:
        info = teleo.run_info()
        assert wait_for(lambda: trace_lines(info) >= post_after, timeout)
        posted = teleo("goal", "post", BOTH[1], "--priority", "5")
        assert posted.returncode == 0, posted.stderr
        assert wait_for(lambda: all(statuses(teleo).get(g) == "achieved" for g in BOTH),
                        timeout), teleo("goal", "list").stdout
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    summary = json.loads(summary_file.read_text())
    assert (teleo.run_dir / "run.png").read_bytes()[:4] == b"\x89PNG"
    return summary


def test_a_small_program_delivers_a_package_posted_mid_run(teleo):
    summary = deliver_two(teleo, FIXTURES / "deliver_ahead.toml", post_after=50, timeout=120)
    assert summary["goals_achieved"] == 2 and summary["achievements"] == {"ME": {"deliveries": 2}}
    assert summary["law_violations"]["ME"]["pedestrian_hits"] == 0


def demo_without_scripted_packet2(folder: Path) -> Path:
    """scenarios/driving_demo.toml less its scripted PACKET2 request."""
    text = (ROOT / "scenarios" / "driving_demo.toml").read_text()
    blocks = re.split(r"(?m)^(?=\[\[goals\]\])", text)
    text = "".join(b for b in blocks if not (b.startswith("[[goals]]") and "PACKET2" in b))
    assert text.count("[[goals]]") == 1 and BOTH[0] in text
    path = folder / "driving_live.toml"
    path.write_text(text.replace('program = "programs/', f'program = "{ROOT}/programs/'))
    return path


def test_the_driving_demo_delivers_both_packages_and_hits_no_pedestrian(teleo, tmp_path):
    scenario = demo_without_scripted_packet2(tmp_path)
    summary = deliver_two(teleo, scenario, post_after=100, timeout=400)
    assert summary["goals_achieved"] == 2 and summary["achievements"]["ME"]["deliveries"] >= 2
    assert summary["law_violations"]["ME"]["pedestrian_hits"] == 0
