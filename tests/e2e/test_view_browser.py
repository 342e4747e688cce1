"""`teleo view` in a real browser: a realtime launch, the view following it, and headless
Chromium (tests/e2e/cdp.py) reading the page while a goal posted with `teleo goal post` goes
from pending or active to satisfied; then the timeline steps back to a cycle where it was
still being worked on."""

from __future__ import annotations

import signal
import subprocess
from pathlib import Path

import pytest
from cdp import Chromium
from e2e_helpers import FIXTURES, ROOT, TELEO, interrupt, wait_for

ROWS = "Object.fromEntries([...document.querySelectorAll('#agents tr.goal')]" \
       ".map(r => [r.dataset.id, r.dataset.status]))"


def realtime_deliver_ahead(folder: Path) -> Path:
    """The deliver-ahead fixture at 20 cycles a second, its program found from anywhere."""
    text = (FIXTURES / "deliver_ahead.toml").read_text()
    text = text.replace("cycles = 0\n", "cycles = 0\ndeadline = 0.05\n")
    text = text.replace('program = "deliver_ahead.tlp"',
                        f'program = "{FIXTURES / "deliver_ahead.tlp"}"')
    path = folder / "deliver_realtime.toml"
    path.write_text(text)
    return path


@pytest.fixture
def view_of_a_launch(teleo, tmp_path):
    """A running realtime launch and `teleo view --port 0` following it; yields (url, teleo)."""
    launcher = teleo.start("launch", str(realtime_deliver_ahead(tmp_path)), "--mode",
                           "realtime")
    viewer = None
    try:
        teleo.run_info()
        viewer = subprocess.Popen([*TELEO, "view", "--port", "0"], cwd=ROOT, env=teleo.env,
                                  stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        first = viewer.stdout.readline()
        assert " at http://127.0.0.1:" in first, first + viewer.stdout.read()
        yield first.split(" at ")[1].split()[0], teleo
    finally:
        if viewer is not None:
            viewer.send_signal(signal.SIGINT)
            assert viewer.wait(30) == 0
        code, out = interrupt(launcher), teleo.launch_output()
        # realtime on a busy machine may leave the car to its safe action for a cycle or
        # two; the run then says so and fails (docs/faults.md), which is not this test's point
        assert code == 0 or (code == 1 and "uncontrolled for" in out), out


def test_the_page_shows_goals_and_their_statuses_changing(view_of_a_launch, tmp_path):
    url, teleo = view_of_a_launch
    with Chromium(tmp_path / "profile") as page:
        page.goto(url)
        assert wait_for(lambda: "g1" in page.evaluate(ROWS), 120), page.evaluate(
            "document.body.innerText")
        # the world is drawn from its map, fetched on its own (after the rows on a busy machine)
        assert wait_for(lambda: page.evaluate("view.map && view.map.domain") == "driving", 60)
        posted = teleo("goal", "post", "(package-delivered PACKET2)", "--priority", "3")
        assert posted.returncode == 0, posted.stderr
        seen: list[str] = []

        def g2_satisfied() -> bool:
            status = page.evaluate(ROWS).get("g2")
            if status and (not seen or seen[-1] != status):
                seen.append(status)
            return status == "satisfied"

        assert wait_for(g2_satisfied, 180), seen
        assert len(seen) >= 2 and seen[0] in {"pending", "active", "suspended"}, seen
        # the process table shows the live executive
        procs = page.evaluate("document.getElementById('procs').innerText")
        assert "ME.executive\tup" in procs, procs
        # step back on the timeline to the cycle where g2 became active
        history = page.evaluate("view.status.goals.ME.g2")
        active = next(h["cycle"] for h in history if h["status"] == "active")
        page.evaluate(f"(() => {{ const s = document.getElementById('slider'); s.value = "
                      f"{active}; s.dispatchEvent(new Event('input')); }})()")
        assert wait_for(lambda: page.evaluate("document.body.dataset.cycle") == str(active), 30)
        assert page.evaluate(ROWS)["g2"] == "active"
        assert page.evaluate("document.getElementById('live').classList.contains('on')") is False
        shot = tmp_path / "view.png"
        page.screenshot(shot)
        assert shot.read_bytes()[:4] == b"\x89PNG"
