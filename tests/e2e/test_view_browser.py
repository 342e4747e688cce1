"""`teleo view` in a real browser (headless Chromium, tests/e2e/cdp.py), in a 1400 x 1000
viewport. Live: a realtime launch and the view following it, while a goal posted with
`teleo goal post` goes from pending or active to satisfied, the timeline steps back to a
cycle where it was being worked on, and the badge goes from live to ended when the launch
stops. Records that `teleo simulate` writes: a city taller than wide fits the window, the
timeline is labelled with cycles, the beliefs panel names the pedestrian that the law stops
for, with the percept behind it; an office record draws its floor at once and keeps its
failed goal, with the reason, in the goal table of every later cycle."""

from __future__ import annotations

import re
import signal
import subprocess
from contextlib import contextmanager
from pathlib import Path

from cdp import Chromium
from e2e_helpers import FIXTURES, ROOT, TELEO, interrupt, wait_for

from tools.records.run_record import RunRecord

ROWS = "Object.fromEntries([...document.querySelectorAll('#agents tr.goal')]" \
       ".map(r => [r.dataset.id, r.dataset.status]))"
NOTES = "Object.fromEntries([...document.querySelectorAll('#agents tr.goal')]" \
        ".map(r => [r.dataset.id, r.querySelector('.note').textContent]))"
STATE = "document.getElementById('state').dataset.state"
LOADED = "typeof view === 'object' && !!(view.frame && view.map && view.status)"
PICTURE = "(() => { const i = document.getElementById('render'); return {header: " \
          "document.body.dataset.cycle, shown: i.dataset.shown ?? (i.complete ? new URL(" \
          "i.currentSrc).searchParams.get('cycle') : null), stale: i.classList.contains(" \
          "'stale'), title: i.title}; })()"
WIDTH, HEIGHT = 1400, 1000


def realtime_deliver_ahead(folder: Path) -> Path:
    """The deliver-ahead fixture at 20 cycles a second, its program found from anywhere."""
    text = (FIXTURES / "deliver_ahead.toml").read_text()
    text = text.replace("cycles = 0\n", "cycles = 0\ndeadline = 0.05\n")
    text = text.replace('program = "deliver_ahead.tlp"',
                        f'program = "{FIXTURES / "deliver_ahead.tlp"}"')
    path = folder / "deliver_realtime.toml"
    path.write_text(text)
    return path


@contextmanager
def page_of_view(teleo, tmp_path: Path, *args: str):
    """`teleo view --port 0 ARGS` and a browser on its page; yields the page."""
    viewer = subprocess.Popen([*TELEO, "view", "--port", "0", *args], cwd=ROOT, env=teleo.env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        first = viewer.stdout.readline()
        assert " at http://127.0.0.1:" in first, first + viewer.stdout.read()
        with Chromium(tmp_path / "profile") as page:
            page.viewport(WIDTH, HEIGHT)
            page.goto(first.split(" at ")[1].split()[0])
            yield page
    finally:
        viewer.send_signal(signal.SIGINT)
        assert viewer.wait(30) == 0


def go_to(page, cycle: int) -> None:
    """Move the timeline's slider to `cycle`, as a person would, and wait for the page."""
    page.evaluate(f"(() => {{ const s = document.getElementById('slider'); s.value = {cycle}; "
                  f"s.dispatchEvent(new Event('input')); }})()")
    assert wait_for(lambda: page.evaluate("document.body.dataset.cycle") == str(cycle), 30)


def simulated(teleo, fixture: Path) -> Path:
    """The record `teleo simulate` writes of a fixture scenario."""
    done = teleo("simulate", str(fixture), timeout=300)
    found = re.search(r"run record written to (\S+)", done.stdout)
    assert found, done.stdout + done.stderr
    return Path(found.group(1))


def test_the_page_shows_goals_and_their_statuses_changing(teleo, tmp_path):
    launcher = teleo.start("launch", str(realtime_deliver_ahead(tmp_path)), "--mode",
                           "realtime")
    code: int | str | None = None
    try:
        teleo.run_info()
        with page_of_view(teleo, tmp_path) as page:
            assert wait_for(lambda: "g1" in page.evaluate(ROWS), 120), page.evaluate(
                "document.body.innerText")
            # the world is drawn from its map, fetched on its own (after the rows when busy)
            assert wait_for(lambda: page.evaluate("view.map && view.map.domain") == "driving",
                            60)
            assert wait_for(lambda: page.evaluate(STATE) == "live", 30), page.evaluate(STATE)
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
            procs = page.evaluate("document.getElementById('procs').innerText")
            assert "ME.executive\tup" in procs, procs
            # step back on the timeline to the cycle where g2 became active
            history = page.evaluate("view.status.goals.ME.g2")
            active = next(h["cycle"] for h in history if h["status"] == "active")
            go_to(page, active)
            assert page.evaluate(ROWS)["g2"] == "active"
            # the beliefs panel of a live cycle, its reasons read from the launch's program
            panel = page.evaluate("document.querySelector('#agents .beliefs').innerText")
            assert "reasons from " in panel and "deliver_ahead.tlp" in panel, panel
            assert page.evaluate("document.getElementById('live').classList.contains('on')") \
                is False
            # the launch stops: the badge says the run has ended (not a green "connected")
            code = interrupt(launcher)
            assert wait_for(lambda: page.evaluate(STATE) == "ended", 60), page.evaluate(STATE)
            assert page.evaluate("document.getElementById('state').textContent") == "run ended"
    finally:
        code = interrupt(launcher) if code is None else code
    # realtime on a busy machine may leave the car to its safe action for a cycle or two;
    # the run then says so and fails (docs/faults.md), which is not this test's point
    out = teleo.launch_output()
    assert code == 0 or (code == 1 and "uncontrolled for" in out), out


def test_a_tall_city_fits_the_window_and_the_law_names_its_pedestrian(teleo, tmp_path):
    record = simulated(teleo, FIXTURES / "view_tall.toml")
    with page_of_view(teleo, tmp_path, str(record)) as page:
        assert wait_for(lambda: page.evaluate(LOADED), 60)
        assert page.evaluate(STATE) == "record"
        assert "live" not in page.evaluate("document.getElementById('at').textContent")
        # the whole city (its map box, 30 m around the streets) and the timeline in the window
        box = page.evaluate("(() => { const r = document.getElementById('map')"
                            ".getBoundingClientRect(), s = view.map.size; return {top: r.top, "
                            "bottom: r.bottom, right: r.right, w: r.width, h: r.height, "
                            "aspect: (s[0] + 60) / (s[1] + 60)}; })()")
        assert box["aspect"] < 1, box  # taller than wide
        assert box["top"] >= 0 and box["bottom"] <= HEIGHT and box["right"] <= WIDTH, box
        assert box["h"] >= 300 and abs(box["w"] / box["h"] - box["aspect"]) < 0.02, box
        strip = page.evaluate("document.getElementById('axis').getBoundingClientRect().bottom")
        assert strip <= HEIGHT, strip
        # the timeline's cycle axis: labels in order, within the cycles held
        first, last = page.evaluate("[view.status.first, view.status.last]")
        ticks = [int(t) for t in page.evaluate(
            "[...document.querySelectorAll('#axis .tick')].map(t => t.textContent)")]
        assert len(ticks) >= 3 and ticks == sorted(ticks), ticks
        assert first <= ticks[0] and ticks[-1] <= last, (first, last, ticks)
        # a cycle where the pedestrian law acts: the panel names the belief that breaks it,
        # the man the agent perceived that cycle, and his distance
        history = page.evaluate("view.status.goals.ME.p1")
        acting = next(h["cycle"] for h in history if h["status"] == "active")
        go_to(page, acting)
        rec = RunRecord(record)
        men = sorted(b[2] for b in rec.by_cycle("beliefs", "ME")[acting]["beliefs"]
                     if b[0] == "pedestrian-ahead")
        assert men, f"no pedestrian-ahead belief at cycle {acting}"
        shown = page.evaluate("[...document.querySelectorAll('.why-goal[data-id=\"p1\"] "
                              ".belief')].map(b => b.dataset.belief)")
        percepts = page.evaluate("[...document.querySelectorAll('.why-goal[data-id=\"p1\"] "
                                 ".percept')].map(p => p.textContent)")
        for man in men[:6]:
            assert f"(pedestrian-ahead ME {man})" in shown, shown
            row = next(p for p in rec.by_cycle("percepts", "ME")[acting]["percepts"]
                       if p[:2] == ["man", man])
            dist = row[row.index("dist") + 1]
            assert any(p.startswith(f"(man {man} ") and f"dist {dist}" in p
                       for p in percepts), (man, dist, percepts)
        assert page.evaluate("document.querySelector('#agents .actions').textContent") \
            == "actions: (*brake 100)"


def test_an_office_record_draws_its_floor_at_once_and_keeps_its_failed_goal(teleo, tmp_path):
    record = simulated(teleo, FIXTURES / "view_office_unreachable.toml")
    with page_of_view(teleo, tmp_path, str(record)) as page:
        # the floor, the domain's own picture, is drawn without a step on the timeline
        assert wait_for(lambda: page.evaluate(
            "(() => { const i = document.getElementById('render'); return !i.hidden && "
            "i.complete && i.naturalWidth > 0; })()"), 30), page.evaluate(
            "document.getElementById('render').outerHTML")
        assert page.evaluate(STATE) == "record"
        failed = [h for h in page.evaluate("view.status.goals.ME.g1") if h["status"] == "failed"]
        assert failed, page.evaluate("view.status.goals.ME.g1")
        at, last = failed[0]["cycle"], page.evaluate("view.status.last")
        assert at < last
        for cycle in (last, at + (last - at) // 2):
            if page.evaluate("document.body.dataset.cycle") != str(cycle):
                go_to(page, cycle)
            assert page.evaluate(ROWS).get("g1") == "failed", (cycle, page.evaluate(ROWS))
            note = page.evaluate(NOTES)["g1"]
            assert f"failed at cycle {at}" in note and "unreachable" in note, note
        go_to(page, at - 1)
        assert page.evaluate(ROWS).get("g1") == "suspended", page.evaluate(ROWS)
        # issue 31, N17: the picture is fetched at most once a second, so while the slider
        # moves it lags the header; a picture of another cycle than the header's is dimmed
        # and says which cycle it shows, and the one of the cycle shown follows
        samples = []
        for cycle in range(at - 1, last + 1, max(1, (last - at) // 12)):
            page.evaluate(f"(() => {{ const s = document.getElementById('slider'); "
                          f"s.value = {cycle}; s.dispatchEvent(new Event('input')); }})()")
            samples.append(page.evaluate(PICTURE))
        go_to(page, last)
        samples.append(page.evaluate(PICTURE))
        lagging = [s for s in samples if s["shown"] != s["header"]]
        assert all(s["stale"] and f"picture of cycle {s['shown']}" in s["title"]
                   for s in lagging), samples
        assert wait_for(lambda: page.evaluate(PICTURE)["shown"] == str(last), 30)
        assert not page.evaluate(PICTURE)["stale"]
