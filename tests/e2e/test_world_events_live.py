"""`teleo event` injects a world event into a running launch and reports the world's verdict
(issue 12, item 2); the world records the outcome in the trace."""

from __future__ import annotations

import json
from pathlib import Path

from e2e_helpers import HOLD_SPEED, interrupt, wait_for


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
        assert "inject: segment: expected a segment id, got None" in bad.stderr
        assert wait_for(lambda: injected(info, "block"), 60), teleo.launch_output()
        for event, reason in (('{"kind": "teleport"}', "unknown kind 'teleport'"),
                              ('{"kind": "block", "segment": "S99"}', "S99"),
                              ('{"kind": "pedestrian", "ahead_of": "YOU", "dist": 5}',
                               "ahead_of: unknown agent 'YOU'"),
                              ('{"kind": "pedestrian", "ahead_of": "ME", "dist": 5, '
                               '"speed": 1e308}', "speed: expected a number in [0, 10]"),
                              ('{"kind": "package", "id": "P9", "address": 4, "street": "B", '
                               '"owner": "ME"}', "package P9 exists already")):
            refused = teleo("event", event)
            assert refused.returncode == 1 and reason in refused.stderr, refused.stderr
        junk = teleo("event", "[1, 2]")
        assert junk.returncode != 0 and 'expected an object with a "kind"' in junk.stderr
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    package, again = injected(info, "package")
    assert package["status"] == "done" and package["event"]["id"] == "P9", package
    assert again["status"] == "failed" and "exists already" in again["reason"], again
    assert [b["status"] for b in injected(info, "block")] == ["failed", "failed"]
    assert "segment" in injected(info, "block")[0]["reason"]
