"""`teleo graph --run RUN` over a real launch (issue 34, pictures; as ROS 2's rqt_graph): the
processes whose liveliness tokens are up, and the keys each publishes and subscribes to; once
the run has ended, its record's senders; a run neither running nor recorded is one line,
exit 1."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET

from e2e_helpers import HOLD_SPEED, interrupt


def test_a_running_launch_is_drawn_as_its_processes_and_keys(teleo, tmp_path):
    nothing = teleo("graph", "--run", "hold-speed-x", "--json")
    assert nothing.returncode == 1 and nothing.stdout == ""
    assert nothing.stderr.startswith("Error: no run 'hold-speed-x' in ") and \
        len(nothing.stderr.splitlines()) == 1 and "nor is there a record of it" in nothing.stderr
    launcher = teleo.start("launch", str(HOLD_SPEED), "--cycles", "100000")
    try:
        info = teleo.run_info()
        run = info["run"]
        out = tmp_path / "run.svg"
        drawn = teleo("graph", "--run", run, "--out", str(out), "--json")
        assert drawn.returncode == 0, drawn.stderr + teleo.launch_output()
        g = json.loads(drawn.stdout)
        procs = {n["label"] for n in g["nodes"] if n["kind"] == "process"}
        assert procs >= {"world", "goals", "ME.perception", "ME.inference", "ME.executive",
                         "launch.record"}, procs
        assert set(info["pids"]) - {"router"} <= procs   # each one started is up (the hub
        # holds no token: it carries the keys, as no node of rqt_graph is the DDS itself)
        edges = {(e["from"], e["to"], e["label"]) for e in g["edges"]}
        root = f"teleo/{run}"
        for src, dst, how in (
                ("proc:world", "world/state", "publishes"),
                ("world/state", "proc:ME.perception", "subscribes"),
                ("proc:ME.perception", "agent/ME/percepts", "publishes"),
                ("agent/ME/percepts", "proc:ME.inference", "subscribes"),
                ("proc:ME.inference", "agent/ME/beliefs", "publishes"),
                ("agent/ME/beliefs", "proc:ME.executive", "subscribes"),
                ("proc:goals", "agent/ME/goal-list", "publishes"),
                ("agent/ME/goal-list", "proc:ME.executive", "subscribes"),
                ("proc:ME.executive", "agent/ME/actions", "publishes"),
                ("agent/ME/actions", "proc:world", "subscribes"),
                ("agent/ME/goals", "proc:goals", "serves"),
                ("world/state", "proc:launch.record", "subscribes")):
            key = lambda x: x if x.startswith("proc:") else f"key:{root}/{x}"  # noqa: E731
            assert (key(src), key(dst), how) in edges, (src, dst, how)
        assert not any("/stats/" in n["id"] for n in g["nodes"])
        svg = ET.fromstring(out.read_text())
        assert sum(1 for x in svg.iter("{http://www.w3.org/2000/svg}g")
                   if "process" in x.get("class", "")) == len(procs)
        stats = json.loads(teleo("graph", "--run", run, "--stats", "--json").stdout)
        assert f"key:{root}/stats/ME.executive" in {n["id"] for n in stats["nodes"]}
    finally:
        interrupt(launcher)
    ended = teleo("graph", "--run", run, "--json")   # the run has ended: drawn from its record
    assert ended.returncode == 0, ended.stderr
    g = json.loads(ended.stdout)
    assert g["title"] == f"run {run} (record): processes and keys"
    assert {n["label"] for n in g["nodes"] if n["kind"] == "process"} >= \
        {"world", "goals", "ME.perception", "ME.inference", "ME.executive"}
    assert ("proc:ME.executive", f"key:teleo/{run}/agent/ME/actions", "publishes") in \
        {(e["from"], e["to"], e["label"]) for e in g["edges"]}
