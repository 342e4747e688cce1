"""`teleo event` injects a world event into a running launch and reports the world's verdict
(issue 12, item 2); the world records the outcome in the trace."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from e2e_helpers import HOLD_SPEED, ROOT, interrupt, wait_for


def trace(info: dict) -> list[dict]:
    """The run's trace lines written so far."""
    path = Path(info["run_dir"]) / "trace.jsonl"
    return [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []


def injected(info: dict, kind: str) -> list[dict]:
    """The outcomes of injected events of `kind` recorded in the run's trace so far."""
    return [e for line in trace(info) for e in line.get("events", []) if e["event"]["kind"] == kind]


def test_a_package_sent_with_teleo_event_appears_in_the_world(teleo):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        sent = teleo("event", '{"kind": "package", "id": "P9", "address": 4, "street": "B", '
                              '"owner": "ME"}')
        assert sent.returncode == 0, sent.stderr
        assert sent.stdout.startswith(f"run {info['run']}: applied at cycle ")
        at = int(sent.stdout.split("applied at cycle ")[1].split(":")[0])
        # the verdict goes out before the state of that cycle, its trace line when the cycle
        # ends (the agents' actions in): the event is in the line of the cycle it names
        assert wait_for(lambda: injected(info, "package"), 60), teleo.launch_output()
        assert [x["cycle"] for x in trace(info) for e in x.get("events", [])
                if e["event"]["kind"] == "package"] == [at]
        # the world's verdict, not "sent": a refusal exits 1 with the world's reason
        bad = teleo("event", '{"kind": "block"}')            # no segment: the world refuses it
        assert bad.returncode == 1, bad.stdout
        assert "the world refused the event at cycle" in bad.stderr
        assert "inject: segment: missing; expected a segment id" in bad.stderr
        assert wait_for(lambda: injected(info, "block"), 60), teleo.launch_output()
        for event, reason in (('{"kind": "teleport"}', "unknown kind 'teleport'"),
                              ('{"kind": "block", "segment": "S99"}', "S99"),
                              ('{"kind": "pedestrian", "ahead_of": "YOU", "dist": 5}',
                               "ahead_of: unknown agent 'YOU'"),
                              ('{"kind": "pedestrian", "ahead_of": "ME", "dist": 5, '
                               '"speed": 1e308}', "speed: expected a number in [0, 10]"),
                              ('{"kind": "package", "id": "P9", "address": 4, "street": "B", '
                               '"owner": "ME"}', "package P9 exists already"),
                              # issue 24: an unknown field, and drill N3's owner (a list)
                              ('{"kind": "pedestrian", "ahead_of": "ME", "dist": 20, '
                               '"colour": "red"}', "inject: unknown field 'colour'; known:"),
                              ('{"kind": "package", "id": "P10", "address": 4, "street": "B", '
                               '"owner": []}', "inject: owner: expected an agent's name, "
                                               "got []")):
            refused = teleo("event", event)
            assert refused.returncode == 1 and reason in refused.stderr, refused.stderr
        junk = teleo("event", "[1, 2]")
        assert junk.returncode != 0 and 'expected an object with a "kind"' in junk.stderr
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    package, again, listed = injected(info, "package")
    assert package["status"] == "done" and package["event"]["id"] == "P9", package
    assert again["status"] == "failed" and "exists already" in again["reason"], again
    assert listed["status"] == "failed" and listed["event"]["owner"] == [], listed
    assert [b["status"] for b in injected(info, "block")] == ["failed", "failed"]
    assert "segment" in injected(info, "block")[0]["reason"]


def test_a_run_lives_through_hundreds_of_random_events_and_spoilt_messages(teleo):
    """Drill d4e over the bus (issue 24): a stranger publishes 300 random world events
    (and asks 5), and spoilt copies of the run's own messages on every key; the world and
    every stage take them all without a restart, the world records an outcome for each event
    it could decode, and the run ends as an undisturbed one does."""
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        assert wait_for(lambda: len(trace(info)) > 5, 60), teleo.launch_output()
        peer = subprocess.run([sys.executable, str(ROOT / "tests" / "e2e" / "hostile_peer.py"),
                               "--scenario", str(HOLD_SPEED), "--events", "300"],
                              cwd=ROOT, env=teleo.env, capture_output=True, text=True,
                              timeout=240)
        assert peer.returncode == 0, peer.stderr
        sent = json.loads(peer.stdout.splitlines()[-1])
        assert sent["published"] + sent["asked"] >= 280 and sent["decodable"] > 150, sent
        assert len(sent["answers"]) == sent["asked"] == 5
        # each asked event: the world's verdict, or the codec's refusal naming the field
        answered = [a for a in sent["answers"] if isinstance(a[0], bool)]
        assert all(isinstance(a[0], bool) or "WorldEvent.event" in a[1]
                   for a in sent["answers"]), sent["answers"]
        scripted = 1   # hold_speed.toml's own pedestrian at cycle 5
        outcomes = lambda: [e for line in trace(info) for e in line.get("events", [])]  # noqa: E731
        want = sent["decodable"] + len(answered) + scripted
        assert wait_for(lambda: len(outcomes()) >= want, 60), (len(outcomes()), want)
        assert len(outcomes()) == want
        refused = [e for e in outcomes() if e["status"] == "failed"]
        assert refused and all(e["reason"].startswith("inject: ") for e in refused)
        lines = len(trace(info))
        assert wait_for(lambda: len(trace(info)) > lines + 10, 60)   # and it goes on
    finally:
        status = interrupt(launcher)
    out = teleo.launch_output()
    assert status == 0, out
    assert "exited with code" not in out and "restarted" not in out, out
    supervision = Path(info["run_dir"]) / "supervision.jsonl"
    events = [json.loads(x) for x in supervision.read_text().splitlines()] \
        if supervision.exists() else []
    assert not [e for e in events if e.get("event") in ("exit", "restart", "gone")], events
    perception_log = (Path(info["run_dir"]) / "logs" / "ME.perception.log").read_text()
    assert "refused: teleo/" in perception_log and "snapshot: cars[0].x" in perception_log
