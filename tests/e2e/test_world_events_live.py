"""`teleo event` injects a world event into a running launch; the world records its outcome."""

from __future__ import annotations

import json
from pathlib import Path

from e2e_helpers import HOLD_SPEED, interrupt, wait_for


def injected(info: dict, kind: str) -> list[dict]:
    """The outcomes of injected events of `kind` recorded in the run's trace so far."""
    path = Path(info["run_dir"]) / "trace.jsonl"
    lines = [json.loads(line) for line in path.read_text().splitlines()] if path.exists() else []
    return [e for line in lines for e in line.get("events", []) if e["event"]["kind"] == kind]


def test_a_package_sent_with_teleo_event_appears_in_the_world(teleo):
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "0")
    try:
        info = teleo.run_info()
        sent = teleo("event", '{"kind": "package", "id": "P9", "address": 4, "street": "B", '
                              '"owner": "ME"}')
        assert sent.returncode == 0, sent.stderr
        assert wait_for(lambda: injected(info, "package"), 60), teleo.launch_output()
        bad = teleo("event", '{"kind": "block"}')            # no segment: the world refuses it
        assert bad.returncode == 0, bad.stderr
        assert wait_for(lambda: injected(info, "block"), 60), teleo.launch_output()
        junk = teleo("event", "[1, 2]")
        assert junk.returncode != 0 and 'expected an object with a "kind"' in junk.stderr
    finally:
        assert interrupt(launcher) == 0, teleo.launch_output()
    (package,) = injected(info, "package")
    assert package["status"] == "done" and package["event"]["id"] == "P9", package
    (block,) = injected(info, "block")
    assert block["status"] == "failed" and "segment" in block["reason"], block
