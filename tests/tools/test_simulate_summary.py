"""`teleo simulate` keeps user goals as a launch does (issue 12, items 7 and 11): ids g1, g2,
... from the goal store, statuses and notes mirrored from each decision (with the hint for an
object no percept mentions), scripted cancels and the summary JSON a launch prints."""

from __future__ import annotations

import json
from pathlib import Path

from click.testing import CliRunner

from tools.cli import cli

ROOT = Path(__file__).resolve().parents[2]
DRIVING = ROOT / "programs" / "driving.tlp"


def scenario(tmp_path: Path, goals: str) -> Path:
    text = (ROOT / "scenarios" / "driving_demo.toml").read_text()
    text = text[:text.index("[[goals]]")].replace('"programs/driving.tlp"', f'"{DRIVING}"')
    path = tmp_path / "s.toml"
    path.write_text(text + goals)
    return path


def test_goal_ids_statuses_notes_and_a_scripted_cancel(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, """
[[goals]]
goal = "(package-delivered PACKET9)"
priority = 6
[[goals]]
goal = "(package-delivered PACKET1)"
priority = 5
at_cycle = 2
[[goals]]
op = "cancel"
goal_id = "g2"
at_cycle = 4
""")
    result = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "6", "--json"])
    summary = json.loads(result.stdout)
    got = {g["id"]: g for g in summary["goals"]}
    # the driving program gives up on a package no percept mentions: the run fails (exit 1)
    # and the summary says which goal failed
    assert result.exit_code == 1, result.output
    assert summary["status"] == "failed" and not summary["completed"]
    assert [f for f in summary["failures"] if "g1 (package-delivered PACKET9)" in f]
    assert [(g["id"], g["goal"], g["posted_cycle"]) for g in summary["goals"]] == [
        ("g1", "(package-delivered PACKET9)", 0), ("g2", "(package-delivered PACKET1)", 2)]
    assert got["g1"]["status"] == "failed"
    assert "no percept mentions PACKET9: is there such an object?" in got["g1"]["note"]
    assert (got["g2"]["status"], got["g2"]["updated_cycle"]) == ("cancelled", 4)
    # each goal's history, from the run record, as a launch's summary has it
    assert [(h["cycle"], h["status"]) for h in got["g2"]["history"]][-1] == (4, "cancelled")
    assert got["g1"]["history"][-1]["status"] == "failed"
    assert (summary["mode"], summary["cycles"]) == ("simulate", 6)
    assert summary["goals_achieved"] == 0 and summary["counters"]["ME"]["deliveries"] == 0


def test_a_scenario_that_runs_until_ctrl_c_needs_a_number_of_cycles(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, "")
    path.write_text(path.read_text().replace("cycles = 650", "cycles = 0"))
    refused = CliRunner().invoke(cli, ["simulate", str(path)])
    assert refused.exit_code == 2 and "cycles = 0 runs a launch until Ctrl-C; a simulation " \
        "needs a number: give --cycles N" in refused.output
    assert not (tmp_path / "runs").exists()                 # nothing ran
    ran = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "3", "--json"])
    assert ran.exit_code == 0 and json.loads(ran.stdout)["cycles"] == 3, ran.output


def test_a_scripted_event_the_world_refuses_fails_the_run(tmp_path, monkeypatch):
    """The scenario did not run as written: the summary says which event and why (an event
    sent with `teleo event` gets its verdict then, and fails nothing)."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, '[[events]]\nat_cycle = 2\nkind = "block"\nsegment = "S999"\n'
                              '[[events]]\nat_cycle = 3\nkind = "pedestrian"\nahead_of = "ME"\n'
                              'dist = 20\n')
    result = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "5", "--json"])
    summary = json.loads(result.stdout)
    assert result.exit_code == 1 and summary["status"] == "failed", result.output
    assert summary["events_refused"] == [{"cycle": 2, "event": {"kind": "block",
                                                                "segment": "S999"},
                                          "reason": "inject: unknown segment 'S999'"}]
    assert summary["failures"] == ['scripted event {"kind": "block", "segment": "S999"} at '
                                   "cycle 2 refused by the world: inject: unknown segment "
                                   "'S999'"]


def test_a_run_stops_at_the_end_of_the_first_cycle_its_until_accepts():
    """simulate(until=...) ends a run once its work is done (bench/office/office.py)."""
    from tools.commands.simulate import simulate
    from world.run_scenario import load_scenario

    scenario = load_scenario(ROOT / "scenarios" / "office_figure6.toml")
    whole = simulate(scenario)

    def both_done(states) -> bool:
        return len(states["ME"].planner.finished) == 2
    cut = simulate(scenario, until=both_done)
    end = next(k for k, r in enumerate(whole.records)
               if r["ME"]["planner"]["finished"] and len(r["ME"]["planner"]["finished"]) == 2)
    assert len(cut.records) == end + 1 < len(whole.records)
    assert cut.records == whole.records[:end + 1]


def test_the_summary_is_the_same_with_or_without_a_record(tmp_path, monkeypatch):
    """Issue 24, #12: `--no-record` dropped each goal's history from the summary. A post, a
    scripted cancel (the goal leaves the goal list) and a priority change, over random
    cycles: the histories told in the loop are those the record gives."""
    import random

    from tools.records import goal_reports

    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    rng = random.Random(11)
    for k in range(3):
        cancel, change = sorted(rng.sample(range(3, 40), 2))
        path = scenario(tmp_path, f"""
[[goals]]
goal = "(package-delivered PACKET1)"
priority = 5
[[goals]]
goal = "(package-delivered PACKET2)"
priority = 6
at_cycle = {rng.randrange(0, 3)}
[[goals]]
op = "priority"
goal_id = "g2"
priority = 4
at_cycle = {change}
[[goals]]
op = "cancel"
goal_id = "g1"
force = true
at_cycle = {cancel}
""")
        cycles = str(rng.randrange(40, 60))
        runs = {}
        for flag in ("", "--no-record"):
            out = tmp_path / f"{k}{flag or 'record'}.json"
            done = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", cycles,
                                            "--summary", str(out), *([flag] if flag else [])])
            assert done.exit_code == 0, done.output
            runs[flag] = (json.loads(out.read_text()), done.output)
        (with_record, text), (without, bare) = runs[""], runs["--no-record"]
        assert without["goals"] == with_record["goals"]
        assert all(g["history"] for g in without["goals"])
        assert goal_reports.with_history(without["goals"], Path(with_record["record"]).parent) \
            == with_record["goals"]                              # as the record tells them
        assert [line for line in bare.splitlines() if line.startswith("    g")] == \
            [line for line in text.splitlines() if line.startswith("    g")]
        assert (without["record"], with_record["record_missing"]) == (None, 0)


def test_simulate_writes_its_summary_file_as_launch_does(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, '[[goals]]\ngoal = "(package-delivered PACKET1)"\npriority = 5\n')
    out = tmp_path / "deep" / "summary.json"
    done = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "5", "--json",
                                    "--summary", str(out), "--no-record"])
    assert done.exit_code == 0
    assert json.loads(out.read_text()) == json.loads(done.stdout)   # the --json object
    assert f"summary written to {out}" in done.stderr
    refused = CliRunner().invoke(cli, ["simulate", str(path), "--summary", str(tmp_path)])
    assert refused.exit_code == 2 and "Traceback" not in refused.output
    assert f"Error: Invalid value for '--summary': File '{tmp_path}' is a directory." \
        in refused.output


def test_the_summary_names_the_run_id_that_explain_takes(tmp_path, monkeypatch):
    """Issue 31 (N11): simulate printed `run driving-demo completed`, the scenario's name,
    and `teleo explain driving-demo` found no record: the summary names the run id."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, '[[goals]]\ngoal = "(package-delivered PACKET1)"\npriority = 5\n')
    done = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "4"])
    assert done.exit_code == 0, done.output
    run = done.output.split()[1]
    assert run.startswith("driving-demo-sim-") and f"runs/{run}/record.mcap" in done.output
    explained = CliRunner().invoke(cli, ["explain", run, "--cycle", "2", "--brief"])
    assert explained.exit_code == 0, explained.output
    assert f"(run {run})" in explained.output
    bare = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "4", "--no-record"])
    assert bare.output.startswith("run driving-demo completed")   # no record, no run id


def test_the_scenario_chooses_whether_a_goal_not_kept_fails_the_run(tmp_path, monkeypatch):
    """Issue 31 (N15): one goal the agent gave up on failed the whole run. The default
    (`[run] status = "goals"`) still fails it; `status = "system"` reports the goal and
    completes; a value that is neither is refused naming the field."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, '[[goals]]\ngoal = "(package-delivered PACKET9)"\npriority = 6\n')
    args = ["simulate", str(path), "--cycles", "6", "--no-record"]
    failed = CliRunner().invoke(cli, [*args, "--json"])
    assert failed.exit_code == 1 and json.loads(failed.stdout)["status"] == "failed"
    kept = CliRunner().invoke(cli, [*args, "--set", "run.status='system'"])
    assert kept.exit_code == 0, kept.output
    assert kept.output.startswith("run driving-demo completed")
    assert "  not kept (not a failure of the run, status = system): goal g1 " \
           "(package-delivered PACKET9) could not be kept: failed (" in kept.output
    data = json.loads(CliRunner().invoke(cli, [*args, "--json", "--set",
                                               "run.status='system'"]).stdout)
    assert (data["status"], data["failures"], data["status_policy"]) == ("completed", [],
                                                                         "system")
    assert data["goals_not_kept"][0].startswith("goal g1 (package-delivered PACKET9)")
    wrong = CliRunner().invoke(cli, [*args, "--set", "run.status='lenient'"])
    assert wrong.exit_code == 1 and "[run].status: expected one of ['goals', 'system'], " \
        "got 'lenient'" in wrong.output


def test_a_refused_scripted_request_is_in_the_summary(tmp_path, monkeypatch):
    """Issue 31 (N13): a scripted cancel the goal store refused was one log line; the
    summary says which request, when and why."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, """
[[goals]]
goal = "(package-delivered PACKET1)"
priority = 5
[[goals]]
op = "cancel"
goal_id = "g1"
at_cycle = 2
[[goals]]
op = "cancel"
goal_id = "g1"
at_cycle = 3
""")
    done = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "5", "--no-record"])
    assert done.exit_code == 0, done.output
    line = next(x for x in done.output.splitlines() if "refused" in x)
    assert line.startswith("  scripted cancel of g1 at cycle 3 refused: "), done.output
    data = json.loads(CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "5",
                                               "--no-record", "--json"]).stdout)
    assert data["requests_refused"] == [line.strip()]


def test_an_empty_learned_file_is_refused_by_check_simulate_and_launch_alike(tmp_path,
                                                                             monkeypatch):
    """Issue 31: launch and simulate took an empty learned file, check refused it."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, '[[goals]]\ngoal = "(package-delivered PACKET1)"\npriority = 5\n')
    empty = tmp_path / "learned.tlp"
    empty.write_text("\n")
    checked = CliRunner().invoke(cli, ["check", str(DRIVING), str(empty)])
    assert checked.exit_code == 1
    for command in (["simulate", str(path), "--cycles", "2"], ["launch", str(path)]):
        refused = CliRunner().invoke(cli, [*command, "--learned", str(empty)])
        assert refused.exit_code == 1, (command, refused.output)
        assert refused.output == f"Error: {empty}:1:1: the file is empty: expected learned " \
            "skills as a run writes them (learned-AGENT.tlp, its first line naming the " \
            f"program; teleo check PROGRAM {empty})\n"
    assert not (tmp_path / "runs").exists() or not list((tmp_path / "runs").rglob("*.mcap"))


def test_step_replays_a_recorded_decision_with_the_runs_goal_ids(tmp_path, monkeypatch):
    """Issue 31 (N21): the `teleo step` command `explain --percepts` suggests gave the
    run's g1 and g2 the ids g3 and g4 (numbered after the program's two goals)."""
    import shlex

    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    path = scenario(tmp_path, '[[goals]]\ngoal = "(package-delivered PACKET1)"\npriority = 5\n'
                    '[[goals]]\ngoal = "(package-delivered PACKET2)"\npriority = 6\n'
                    'at_cycle = 2\n')
    done = CliRunner().invoke(cli, ["simulate", str(path), "--cycles", "5", "--json"])
    run = json.loads(done.stdout)["run"]
    told = CliRunner().invoke(cli, ["explain", run, "--cycle", "4", "--percepts"]).stdout
    percepts = tmp_path / "p.txt"
    percepts.write_text(told)
    hint = next(x for x in told.splitlines() if "replay the decision: " in x)
    command = shlex.split(hint.split("replay the decision: ", 1)[1].replace("FILE",
                                                                            str(percepts)))
    assert "g1=(package-delivered PACKET1):5" in command
    assert "g2=(package-delivered PACKET2):6" in command
    stepped = CliRunner().invoke(cli, [*command[1:], "--json"])
    assert stepped.exit_code == 0, stepped.output
    goals = json.loads(stepped.stdout)["decision"]["goals"]
    assert [(g["id"], g["goal"]) for g in goals if g["id"].startswith("g")] == [
        ("g1", "(package-delivered PACKET1)"), ("g2", "(package-delivered PACKET2)")]
