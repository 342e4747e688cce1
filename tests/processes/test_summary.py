"""The run summary tells the truth from the run folder's files, whatever happened to the
world (drill F5: a killed world was reported as "0 cycles"), and its status says whether
the run failed (docs/faults.md, "What counts as a failed run")."""

from __future__ import annotations

import json
from pathlib import Path

import click
from click.testing import CliRunner

from bus.cycle import CycleReport
from tools.records import run_status, summary
from world.domain import get_domain
from world.recorder import Recorder

BASE = {"run": "r1", "scenario": "s.toml", "mode": "lockstep", "seed": 7,
        "cycles_requested": 50}


def write_run(folder: Path, cycles: int, reports: dict[int, CycleReport] | None = None,
              finish: bool = True) -> None:
    """A run folder as the world process leaves it, with the real recorder and world."""
    world = get_domain("driving").create({}, 1, ["ME"])
    rec = Recorder(folder, render_every=10)
    rec.event("ready", cycle=0)
    for t in range(cycles):
        report = (reports or {}).get(t, CycleReport(t, {"ME": ()}))
        applied = {"ME": world.safe_actions("ME") if "ME" in report.noop else [["*gas", 20]]}
        snap = world.snapshot_dict()
        world.apply_actions("ME", applied["ME"])
        world.step()
        rec.cycle(t, snap, applied, [], report, 0.0)
    if finish:
        rec.finish(cycles >= 50, 1.0, "done")
    else:
        for f in (rec.trace, rec.snaps, rec.health):
            f.close()


def goals(folder: Path, *entries) -> None:
    (folder / summary.GOALS_FILE).write_text(json.dumps({"version": 1, "goals": list(entries)}))


def goal(gid: str, status: str) -> dict:
    return {"id": gid, "agent": "ME", "goal": f"(package-delivered {gid})", "priority": 5,
            "status": status}


def test_a_clean_run_completes(tmp_path):
    write_run(tmp_path, 50)
    goals(tmp_path, goal("g1", "achieved"))
    s = summary.build(tmp_path, BASE, {"goals": 0})
    assert (s["status"], s["cycles"], s["failures"], run_status.exit_code(s)) == (
        "completed", 50, [], 0)


def test_a_killed_world_still_counts_every_cycle_that_ran(tmp_path):
    write_run(tmp_path, 31, finish=False)  # no world-final.json, as after a SIGKILL
    s = summary.build(tmp_path, BASE, {"world": 3}, left_down=("world",),
                      ended="the world exited with code -9 and was not restarted")
    assert s["cycles"] == 31 and s["status"] == "failed" and run_status.exit_code(s) == 1
    assert "world gave up (left down after 3 restart(s))" in s["failures"]
    assert s["counters"]["ME"]["deliveries"] == 0  # the last cycle's counters, from the trace


def test_uncontrolled_cycles_stalls_and_dead_stages_are_counted_and_shown(tmp_path):
    reports = {
        10: CycleReport(10, {"ME": ()}, late=("ME.inference",), noop=("ME",)),
        11: CycleReport(11, {"ME": ()}, dead=("ME.inference",), noop=("ME",)),
        20: CycleReport(20, {"ME": ()}, stalled=("ME.inference",), elapsed_ms=2100.0),
    }
    write_run(tmp_path, 50, reports)
    s = summary.build(tmp_path, BASE, {"ME.inference": 1})
    assert s["uncontrolled"] == {"ME": 2}
    assert s["late_stages"] == {"ME.inference": 1} and s["dead_stages"] == {"ME.inference": 1}
    assert s["stalls"] == [{"cycle": 20, "seconds": 2.1, "stages": ["ME.inference"]}]
    assert s["status"] == "failed" and s["failures"] == [
        "ME uncontrolled for 2 cycle(s) (the world applied its safe action)"]
    printed = CliRunner().invoke(_echo, [json.dumps(s)]).output
    assert "run r1 FAILED: 50 cycles" in printed
    assert "dead stages: 1 cycle(s) (ME.inference 1)" in printed
    assert "stalls: 1 (ME.inference 2.1 s at cycle 20)" in printed
    # the safe action is what the trace says was applied in those cycles
    lines = (tmp_path / "trace.jsonl").read_text().splitlines()
    assert json.loads(lines[10])["actions"] == {"ME": [["*brake", 100]]}


def test_a_failed_goal_fails_the_run_and_an_impasse_does_not(tmp_path):
    write_run(tmp_path, 50)
    goals(tmp_path, goal("g1", "failed") | {"note": "no path"}, goal("g2", "impasse"))
    s = summary.build(tmp_path, BASE, {})
    assert s["failures"] == ["goal g1 (package-delivered g1) could not be kept: failed "
                             "(no path)"]


def test_a_stop_asked_for_before_the_end_is_an_interruption(tmp_path):
    write_run(tmp_path, 20)
    stopped = summary.build(tmp_path, BASE, {}, requested_stop=True)
    assert stopped["status"] == "interrupted" and run_status.exit_code(stopped) == 130
    died = summary.build(tmp_path, BASE, {})
    assert died["status"] == "failed" and "the world stopped at cycle 20 of 50" in \
        died["failures"][0]
    forever = summary.build(tmp_path, BASE | {"cycles_requested": 0}, {}, requested_stop=True)
    assert forever["status"] == "completed"


def test_a_goal_store_of_the_wrong_shape_does_not_break_the_summary(tmp_path):
    write_run(tmp_path, 50)
    for bad in ('{"version": 1, "goals": [1, "x", null]}', "[]", "null", '{"goals": 3}',
                "not json"):
        (tmp_path / summary.GOALS_FILE).write_text(bad)
        s = summary.build(tmp_path, BASE, {})
        assert s["goals"] == [] and s["status"] == "completed", bad


@click.command()
@click.argument("doc")
def _echo(doc: str) -> None:
    summary.echo(json.loads(doc))


def test_the_summary_gives_each_process_share_of_the_cycle():
    """issue 13: the launch summary says where a lockstep cycle's time goes."""
    from tools.records.summary import cycle_time

    timing = {"cycle": 800.0, "world": 200.0,
              "stages": {"ME.executive": 300.0, "ME.perception": 100.0, "goals": 50.0}}
    got = cycle_time(timing, 100)
    assert got["ms"] == 10.0
    assert list(got["shares"]) == ["world", "goals", "ME.perception", "ME.executive",
                                   "bus and waits"]
    assert got["shares"] == {"world": 20.0, "goals": 5.0, "ME.perception": 10.0,
                             "ME.executive": 30.0, "bus and waits": 35.0}
    assert cycle_time(None, 100) == {} and cycle_time(timing, 0) == {}


def test_state_and_learned_files_set_aside_are_named_and_the_run_still_completes(tmp_path):
    """Drills 2026-12-04 D1/D4: an unreadable state file is kept, renamed, and named."""
    write_run(tmp_path, 50)
    (tmp_path / "learned-ME.tlp").write_bytes(b"\xff\xfe")   # read, not a crash
    (tmp_path / "state-ME.json.bad").write_bytes(b"\xff\xfe\x00binary")
    (tmp_path / "learned-ME.tlp.bad-2").write_text("(")
    s = summary.build(tmp_path, BASE, {})
    assert s["status"] == "completed"
    assert s["set_aside"] == [str(tmp_path / "learned-ME.tlp.bad-2"),
                              str(tmp_path / "state-ME.json.bad")]
    out = CliRunner().invoke(click.command()(lambda: summary.echo(s))).output
    assert f"SET ASIDE: {tmp_path / 'state-ME.json.bad'} could not be read back" in out


def _record_of(folder: Path, cycles: range) -> None:
    """A run record holding the world states of `cycles` only."""
    from bus import keys
    from bus.messages import Envelope, WorldState
    from bus.record import message_record
    from tools.records.run_record import RECORD_FILE, RecordWriter

    with RecordWriter(folder / RECORD_FILE, "r1") as rec:
        for t in cycles:
            msg = WorldState(Envelope(1, "r1", t, "world", 99), {"time": t}, {}, [])
            rec.add(keys.world_state("r1"), message_record(keys.world_state("r1"), msg))


def test_a_record_that_dropped_cycles_fails_the_run(tmp_path):
    """Drills 2026-12-04 D9: the record lacked 64,734 of 65,712 cycles and the run ended
    "completed"."""
    write_run(tmp_path, 50)
    goals(tmp_path, goal("g1", "achieved"))
    _record_of(tmp_path, range(0, 20))
    s = summary.build(tmp_path, BASE, {})
    assert (s["status"], s["record_missing"], s["record_gaps"]) == ("failed", 30, [[20, 49]])
    assert any("lacks the world states of 30 of 50 cycles (cycles 20-49)" in f
               for f in s["failures"])
    whole = tmp_path / "whole"
    whole.mkdir()
    write_run(whole, 50)
    goals(whole, goal("g1", "achieved"))
    _record_of(whole, range(0, 50))
    assert summary.build(whole, BASE, {})["status"] == "completed"


def test_a_drain_cut_short_on_request_leaves_the_run_interrupted(tmp_path):
    write_run(tmp_path, 30, finish=False)
    _record_of(tmp_path, range(0, 20))
    s = summary.build(tmp_path, BASE, {}, requested_stop=True,
                      recorder={"cut_short": True, "failed": {}})
    assert s["status"] == "interrupted"


def test_a_stall_in_progress_at_the_stop_is_listed(tmp_path):
    """Drill d2b: Ctrl-C during a stall; the stall the world was in went unlisted."""
    from world.recorder import HEALTH

    write_run(tmp_path, 30, finish=False)
    with (tmp_path / HEALTH).open("a") as f:   # as world/process.py writes it at the stop
        f.write(json.dumps({"kind": "stalled", "t": 1.0, "cycle": 30, "seconds": 1.04,
                            "stalled": ["ME.inference"], "at_stop": True}) + "\n")
    s = summary.build(tmp_path, BASE, {}, requested_stop=True)
    assert s["stalls"] == [{"cycle": 30, "seconds": 1.04, "stages": ["ME.inference"],
                            "at_stop": True}]
    printed = CliRunner().invoke(_echo, [json.dumps(s)]).output
    assert "stalls: 1 (ME.inference 1.04 s at cycle 30 (still stalled at the stop))" in printed


def test_a_launch_whose_scenario_says_status_system_is_not_failed_by_a_goal(tmp_path):
    """Issue 31 (N13, N15), a launch's side: `[run] status = "system"` (the launcher puts
    it in the base as status_policy) reports a failed goal without failing the run; the
    goal store's refused scripted requests are printed."""
    write_run(tmp_path, 50)
    refused = "scripted cancel of g1 at cycle 30 refused: g1: already achieved (force = true)"
    (tmp_path / summary.GOALS_FILE).write_text(json.dumps({
        "version": 1, "goals": [goal("g1", "failed") | {"note": "no path"}],
        "refused": [refused]}))
    strict = summary.build(tmp_path, BASE, {})
    assert strict["status"] == "failed" and strict["requests_refused"] == [refused]
    lenient = summary.build(tmp_path, {**BASE, "status_policy": "system"}, {})
    assert (lenient["status"], lenient["failures"]) == ("completed", [])
    assert lenient["goals_not_kept"] == ["goal g1 (package-delivered g1) could not be "
                                         "kept: failed (no path)"]
    printed = CliRunner().invoke(click.command()(lambda: summary.echo(lenient))).output
    assert "  not kept (not a failure of the run, status = system): goal g1 " \
           "(package-delivered g1) could not be kept: failed (no path)" in printed
    assert f"  {refused}" in printed.splitlines()
