"""`teleo record`, `teleo replay` and `teleo echo` as real subprocesses on the bus."""

from __future__ import annotations

import json
import subprocess

from bus_helpers import python

from bus import keys
from bus.messages import Percepts, WorldEvent
from bus.node import open_node
from bus.record import read_recording

TELEO = ("-c", "from tools.cli import main; main()")


def test_record_then_replay_gives_back_the_same_messages(cfg, run_id, tmp_path):
    path = tmp_path / "run.rec"
    key = keys.percepts(run_id, "A")
    sent = []
    with open_node(cfg, run_id, "test") as node:
        recorder = python(*TELEO, "record", str(path), "--run", run_id, "--count", "3",
                          *cfg.to_args())
        assert node.presence.wait_for(lambda alive: "record" in alive, 30)
        for t in range(3):
            sent.append(Percepts(node.envelope(t), "A", (["self", "A", "speed", float(t)],)))
            node.publish(key, sent[-1])
        assert recorder.wait(30) == 0
        header, samples = read_recording(str(path))
        assert header["run"] == run_id and [s.key for s in samples] == [key] * 3

        inbox = node.subscribe(key)
        replayer = python(*TELEO, "replay", str(path), "--speed", "0", "--wait", "30",
                          *cfg.to_args())
        got = [inbox.get(timeout=30) for _ in range(3)]
        assert replayer.wait(30) == 0
    assert got == sent


def test_echo_prints_decoded_json_lines(cfg, run_id):
    key = keys.world_events(run_id)
    with open_node(cfg, run_id, "test") as node:
        echo = python(*TELEO, "echo", f"teleo/{run_id}/**", "--count", "1", "--filter",
                      "blocked", *cfg.to_args(), stdout=subprocess.PIPE, text=True)
        assert not node.wait_matching([key], 30)
        node.publish(key, WorldEvent(node.envelope(4), {"kind": "other"}))
        node.publish(key, WorldEvent(node.envelope(5), {"kind": "road-blocked"}))
        out, _ = echo.communicate(timeout=30)
    line = json.loads(out.strip())
    assert line["key"] == key and line["kind"] == "WorldEvent"
    assert line["msg"]["event"] == {"kind": "road-blocked"} and line["msg"]["env"]["cycle"] == 5
