"""The SCS demo through the real processes (issue 9): scenarios/errands_demo.toml, where one
errand, (errands-done ME), is achieved by an SCS body (programs/errands.tlp): a do* route
choosing each next stop by utility, inactive while a law is broken. The summary shows the
body's outcomes. Then the executive is killed mid-route: its body thread and world model
come back through the world (docs/bus.md, "Agent memory") and the route goes on from where
it was instead of starting again."""

from __future__ import annotations

import json
import os
import signal

from e2e_helpers import ROOT, interrupt, trace_lines, wait_for

SCENARIO = ROOT / "scenarios" / "errands_demo.toml"
SERVED = [["served", "ME", p] for p in ("PACKET1", "PACKET2", "PACKET3")]


def test_the_errands_body_delivers_every_package_and_the_summary_shows_it(teleo):
    summary_file = teleo.run_dir / "summary.json"
    done = teleo("launch", str(SCENARIO), "--summary", str(summary_file), timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    summary = json.loads(summary_file.read_text())
    assert summary["completed"] and summary["goals_achieved"] == 1
    assert summary["achievements"] == {"ME": {"deliveries": 3}}
    assert sum(summary["law_violations"]["ME"].values()) == 0
    body = summary["bodies"]["ME"]
    assert body["tally"] == {"bodies ended: goal achieved": 1, "facts asserted": 4,
                             "facts retracted": 1, "subgoals achieved": 3}
    chosen = {c["label"].split(" when ")[1].split()[0]: (c["chosen"], c["succeeded"])
              for c in body["choices"]}
    assert chosen == {"(stop-ahead": (1, 1), "(nearest-stop": (2, 2)}
    assert body["model"] == SERVED                      # on-route retracted at the end
    out = done.stdout
    assert "ME SCS bodies: bodies ended: goal achieved 1, facts asserted 4" in out
    assert "when (stop-ahead ?self ?p ?d)" in out and "world model: (served ME PACKET1)" in out


def test_a_killed_executive_resumes_its_route_from_the_worlds_copy_of_its_memory(teleo):
    summary_file = teleo.run_dir / "summary.json"
    launcher = teleo.start("launch", str(SCENARIO), "--summary", str(summary_file))
    try:
        info = teleo.run_info()
        assert wait_for(lambda: trace_lines(info) >= 330, 120)   # PACKET1 delivered by now
        killed = info["pids"]["ME.executive"]
        os.kill(killed, signal.SIGKILL)
        assert wait_for(lambda: teleo.run_info()["pids"]["ME.executive"] != killed, 60), \
            teleo.launch_output()
        assert wait_for(lambda: launcher.poll() is not None, 300), teleo.launch_output()
    finally:
        if launcher.poll() is None:
            interrupt(launcher)
    assert launcher.returncode == 0, teleo.launch_output()
    summary = json.loads(summary_file.read_text())
    assert summary["restarts"] == {"ME.executive": 1}
    assert summary["achievements"] == {"ME": {"deliveries": 3}}
    body = summary["bodies"]["ME"]
    # a thread started afresh would have asserted (on-route ME) a second time
    assert body["tally"]["facts asserted"] == 4 and body["model"] == SERVED
    assert sum(c["chosen"] for c in body["choices"]) == 3
