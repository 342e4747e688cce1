"""`teleo echo --list` and `teleo hz` over the driving demo launched in realtime (issue 25),
as `ros2 topic list -v` and `ros2 topic hz`/`bw`: every key of the run with its kind and its
publisher, and rates near the run's 10 cycles a second (its deadline is 0.1 s); each tool says
which run it reached in one short line, and nothing with --quiet."""

from __future__ import annotations

import json

import pytest
from e2e_helpers import ROOT, interrupt

DEMO = ROOT / "scenarios" / "driving_demo.toml"
PER_CYCLE = {  # key -> (kind, publisher): one message a cycle each
    "world/state": ("WorldState", "world"),
    "agent/ME/percepts": ("Percepts", "ME.perception"),
    "agent/ME/beliefs": ("Beliefs", "ME.inference"),
    "agent/ME/intention": ("Intention", "ME.executive"),
    "agent/ME/actions": ("Actions", "ME.executive"),
    "agent/ME/goal-list": ("GoalList", "goals"),
    "stats/world": ("ProcessStats", "world"),
    "stats/goals": ("ProcessStats", "goals"),
    "stats/ME.perception": ("ProcessStats", "ME.perception"),
    "stats/ME.inference": ("ProcessStats", "ME.inference"),
    "stats/ME.executive": ("ProcessStats", "ME.executive"),
}
CYCLES_PER_S = 10.0   # the demo's deadline, 0.1 s: the realtime period


@pytest.fixture(scope="module")
def demo(tmp_path_factory):
    from e2e_helpers import Teleo

    teleo = Teleo(tmp_path_factory.mktemp("demo"))
    launcher = teleo.start("launch", str(DEMO), "--mode", "realtime", "--cycles", "0",
                           "--no-record")
    try:
        yield teleo, teleo.run_info()["run"]
    finally:
        interrupt(launcher)


def test_echo_list_gives_every_key_with_its_kind_rate_size_and_publisher(demo):
    teleo, run = demo
    done = teleo("echo", "--list", "--seconds", "4", "--json")
    assert done.returncode == 0, done.stderr
    said = done.stderr.splitlines()
    assert len(said) == 1 and said[0].startswith(f"run {run} (router tcp/127.0.0.1:")
    assert said[0].endswith(f"): listing the keys of teleo/{run}/**"), said
    listed = {k["key"]: k for k in json.loads(done.stdout)}
    assert set(PER_CYCLE) <= set(listed), sorted(listed)
    for key, (kind, publisher) in PER_CYCLE.items():
        row = listed[key]
        assert row["kinds"] == [kind] and row["publishers"] == [publisher], row
        assert 0.4 * CYCLES_PER_S <= row["rate"] <= 1.3 * CYCLES_PER_S, row
        assert row["mean_size"] > 50 and row["count"] >= 10, row
    table = teleo("echo", "agent/ME/**", "--list", "--seconds", "2", "-q")
    assert table.returncode == 0 and table.stderr == "", table.stderr
    rows = [line.split() for line in table.stdout.splitlines()]
    assert rows[0][:3] == ["KEY", "KIND", "RATE/s"]
    assert {r[0] for r in rows[1:]} == {k for k in PER_CYCLE if k.startswith("agent/ME/")}
    assert all(r[4] in {"ME.perception", "ME.inference", "ME.executive", "goals"}
               for r in rows[1:])


def test_hz_gives_the_rate_the_period_and_the_bytes_per_second(demo):
    teleo, run = demo
    done = teleo("hz", "world/state", "--bw", "--seconds", "5", "--json", "--window", "30")
    assert done.returncode == 0, done.stderr
    assert done.stderr.startswith(f"run {run} (router tcp/127.0.0.1:") and \
        done.stderr.rstrip().endswith(f": rates of teleo/{run}/world/state")
    reports = [json.loads(line) for line in done.stdout.splitlines()]
    assert len(reports) >= 4 and {r["key"] for r in reports} == {"world/state"}
    last = reports[-1]
    assert 0.6 * CYCLES_PER_S <= last["rate"] <= 1.3 * CYCLES_PER_S, last
    assert last["messages"] == 30   # the window
    assert last["period_min"] <= 1 / last["rate"] <= last["period_max"]
    assert last["period_std"] < last["period_max"]
    assert last["bytes_per_s"] == pytest.approx(last["rate"] * last["mean_size"], rel=0.25)
    lines = teleo("hz", "agent/*/actions", "--seconds", "3", "-q")
    assert lines.returncode == 0 and lines.stderr == "", lines.stderr
    assert lines.stdout.splitlines()[-1].startswith("agent/ME/actions: ")
    assert " msg/s  period min " in lines.stdout and "kB" not in lines.stdout
    nothing = teleo("hz", "agent/NOBODY/actions", "--seconds", "1", "-q")
    assert nothing.returncode == 1 and nothing.stderr == (
        f"Error: no message on teleo/{run}/agent/NOBODY/actions within 1 s: is the run going "
        "(teleo inspect), and the key expression right?\n")
