"""The web view's timeline holds a live lockstep launch (issue 34, item 1): its pause, step and
resume buttons ask the world as `teleo pause`, `step-run` and `resume` do, and the page shows
the world's verdict; the run is held between cycles meanwhile (headless Chromium,
tests/e2e/cdp.py)."""

from __future__ import annotations

import json
import urllib.error
import urllib.request
from pathlib import Path

from e2e_helpers import HOLD_SPEED, interrupt, trace_lines, wait_for
from test_view_browser import LOADED, page_of_view

HELD = "document.getElementById('held')"


def _press(page, button: str, starts: str) -> str:
    """Click `button` and wait for the world's verdict, which is returned."""
    page.evaluate(f"{HELD}.textContent = ''; document.getElementById('{button}').click()")
    assert wait_for(lambda: page.evaluate(f"{HELD}.textContent").startswith(starts), 60), \
        page.evaluate(f"{HELD}.textContent")
    return page.evaluate(f"{HELD}.textContent")


def test_the_timeline_pauses_steps_and_resumes_a_live_launch(teleo, tmp_path):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        with page_of_view(teleo, tmp_path) as page:
            assert wait_for(lambda: page.evaluate(LOADED), 60)
            assert wait_for(lambda: page.evaluate(
                "!document.getElementById('hold').hidden"), 30)
            held = _press(page, "pause", "paused at cycle ")
            k = int(held.split()[-1])
            assert trace_lines(info) == k      # cycles before k are recorded, k has not begun
            assert _press(page, "step", "paused") == f"paused at cycle {k + 1} after 1 cycles"
            assert trace_lines(info) == k + 1
            assert _press(page, "resume", "running") == f"running at cycle {k + 1}"
            origin = page.evaluate("location.origin")
            plain = urllib.request.Request(f"{origin}/api/control", data=b'{"op": "pause"}',
                                           headers={"Content-Type": "text/plain"})
            try:
                urllib.request.urlopen(plain, timeout=30)
                raise AssertionError("a request of another kind than JSON was served")
            except urllib.error.HTTPError as exc:
                assert exc.code == 415 and json.loads(exc.read())["ok"] is False
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    health = [json.loads(x) for x in (Path(info["run_dir"]) / "health.jsonl").read_text()
              .splitlines()]
    assert [(h["kind"], h["cycle"]) for h in health if h["kind"] in ("paused", "resumed")] == [
        ("paused", k), ("resumed", k), ("paused", k + 1), ("resumed", k + 1)]
