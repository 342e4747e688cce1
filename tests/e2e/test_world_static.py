"""A world's static configuration goes to its readers once a run, not in every world state
(issue 35): over a real launch, the world states on the bus lack the driving world's config;
the perception stage, a record started mid-run, a view opened mid-run and a view following a
replay of that record all have it, asked of the world (or of the replay) as it was sent once
before they came."""

from __future__ import annotations

import json
import signal
import subprocess
import urllib.request

from e2e_helpers import HOLD_SPEED, ROOT, TELEO, interrupt, trace_lines, wait_for

from tools.records.run_record import RunRecord


def _map_of_view(teleo, *args: str) -> dict:
    """`teleo view --port 0 ARGS`'s /api/map once it draws a world ({} if it never does)."""
    viewer = subprocess.Popen([*TELEO, "view", "--port", "0", *args], cwd=ROOT, env=teleo.env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        url = viewer.stdout.readline().split(" at ")[1].split()[0]
        got: dict = {}

        def drawn() -> bool:
            got.update(json.loads(urllib.request.urlopen(url + "api/map", timeout=10).read()))
            return bool(got.get("segments"))

        wait_for(drawn, 60)
        return got
    finally:
        viewer.send_signal(signal.SIGINT)
        viewer.wait(30)


def test_the_static_part_is_sent_once_and_every_reader_has_it(teleo, tmp_path):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0", "--no-record")
    try:
        info = teleo.run_info()
        assert wait_for(lambda: trace_lines(info) > 20, 60), teleo.launch_output()
        # the perception stage put the config back: its percepts name the streets
        shown = teleo("echo", "agent/ME/percepts", "--seconds", "5")
        assert shown.returncode == 0 and '"segment"' in shown.stdout, shown.stderr
        state = teleo("echo", "world/state", "--seconds", "5")
        assert state.returncode == 0 and '"cars"' in state.stdout, state.stderr
        assert '"config"' not in state.stdout and "ns_streets" not in state.stdout
        # a record started after the world published it still holds it, once
        path = tmp_path / "mid.mcap"
        assert teleo("record", str(path), "--seconds", "2").returncode == 0
        told = [r for _, r in RunRecord(path, raw=True).records() if r["kind"] == "WorldStatic"]
        assert len(told) == 1 and told[0]["static"]["config"]["ns_streets"] == ["A", "B", "C"]
        states = [r["snapshot"] for _, r in RunRecord(path).kinds("state")]
        assert states and all(s["config"] == told[0]["static"]["config"] for s in states)
        # so does a view opened now: its map is the city's
        live = _map_of_view(teleo)
        assert len(live["segments"]) == 12, live        # 3 x 3 streets: 12 blocks
    finally:
        stopped = interrupt(launcher)
    assert stopped == 0, teleo.launch_output()
    # a view following a replay of that record asks the replay, which answers as the world
    replay = subprocess.Popen([*TELEO, "replay", str(path), "--rate", "5", "--loop"], cwd=ROOT,
                              env=teleo.env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    try:
        said = replay.stderr.readline()
        hub = said.split("--connect ")[1].split("`")[0]
        followed = _map_of_view(teleo, "--connect", hub, "--run", info["run"])
        assert len(followed.get("segments", ())) == 12, (said, followed)
    finally:
        replay.send_signal(signal.SIGINT)
        replay.wait(30)
