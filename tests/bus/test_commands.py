"""`teleo record`, `teleo replay` and `teleo echo` as real subprocesses on the bus."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from bus_helpers import ROOT, python

from bus import keys
from bus.messages import Percepts, WorldEvent, WorldState
from bus.node import open_node
from tools.records.run_record import RunRecord

TELEO = ("-c", "from tools.cli import main; main()")


def test_record_then_replay_gives_back_the_same_messages(cfg, run_id, tmp_path):
    path = tmp_path / "run.mcap"
    state, key = keys.world_state(run_id), keys.percepts(run_id, "A")
    sent = []
    with open_node(cfg, run_id, "test") as node:
        recorder = python(*TELEO, "record", str(path), "--run", run_id, "--count", "6",
                          *cfg.to_args())
        assert node.presence.wait_for(lambda alive: "record" in alive, 30)
        for t in range(3):
            sent.append(WorldState(node.envelope(t), {"time": t * 0.1}, {}, []))
            node.publish(state, sent[-1])
            sent.append(Percepts(node.envelope(t), "A", (["self", "A", "speed", float(t)],)))
            node.publish(key, sent[-1])
        assert recorder.wait(30) == 0
        rec = RunRecord(path)
        assert rec.run == run_id and [k for k, _ in rec.records()] == [state, key] * 3
        # MCAP log time is the cycle's world time [ns]; percepts carry their derived self
        assert [r["self"] for _, r in rec.kinds("percepts")] == [{"speed": float(t)}
                                                                 for t in range(3)]

        inbox = node.subscribe(keys.run_all(run_id))
        replayer = python(*TELEO, "replay", str(path), "--speed", "0", "--wait", "30",
                          *cfg.to_args(), stderr=subprocess.PIPE, text=True)
        got = [inbox.get(timeout=30) for _ in range(6)]
        _, said = replayer.communicate(timeout=30)
        assert replayer.returncode == 0, said
    assert got == sent
    assert f"replayed 6 messages (3 cycles) of run {run_id} to router {cfg.connect[0]}" in said


def test_replay_without_a_launch_plays_to_its_own_router_and_a_dead_one_is_refused(
        tmp_path, run_id):
    from tools.records.run_record import RecordWriter

    path = tmp_path / "empty.mcap"
    RecordWriter(path, run_id).close()
    env = dict(os.environ, PYTHONPATH=str(ROOT), TELEO_RUN_DIR=str(tmp_path / "no-runs"))
    nobody = subprocess.run([sys.executable, *TELEO, "replay", str(path)], cwd=ROOT, env=env,
                            capture_output=True, text=True, timeout=60)
    said = nobody.stderr
    assert nobody.returncode == 0, said   # issue 25: a router of its own, as ros2 bag play
    assert "replayed 0 messages (0 cycles)" in said and "of its own" in said, said
    dead_port = python(*TELEO, "replay", str(path), "--connect", "tcp/127.0.0.1:9",
                       stderr=subprocess.PIPE, text=True)
    _, said = dead_port.communicate(timeout=60)
    assert dead_port.returncode == 1 and "no router answers at tcp/127.0.0.1:9" in said, said


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


def test_echo_of_a_key_that_carries_nothing_says_so_as_hz_does(cfg, run_id):
    """Issue 31 (N10): `echo nonexistent/key --seconds 3` printed nothing and exited 0,
    where `hz` names the key and asks whether the run is going."""
    done = python(*TELEO, "echo", f"teleo/{run_id}/nonexistent/key", "--seconds", "1",
                  *cfg.to_args(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    out, err = done.communicate(timeout=60)
    assert done.returncode == 1 and out == ""
    assert f"Error: no message on teleo/{run_id}/nonexistent/key within 1 s: is the run " \
           "going (teleo inspect), and the key expression right?" in err
    key = keys.world_events(run_id)
    with open_node(cfg, run_id, "test") as node:
        echo = python(*TELEO, "echo", f"teleo/{run_id}/**", "--seconds", "4", "--filter",
                      "nowhere", *cfg.to_args(), stdout=subprocess.PIPE,
                      stderr=subprocess.PIPE, text=True)
        assert not node.wait_matching([key], 30)
        node.publish(key, WorldEvent(node.envelope(4), {"kind": "other"}))
        out, err = echo.communicate(timeout=60)
    assert echo.returncode == 1 and out == ""
    assert f"message(s) on teleo/{run_id}/** within 4 s, none containing 'nowhere'" in err
