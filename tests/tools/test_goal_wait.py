"""What `teleo goal post --wait` says about a goal (tools/commands/goal_wait.py), fed with the
intentions and goal lists of real runs recorded by `teleo simulate`: a delivery followed to
achieved with its skill path, a goal the problem solver gives up (failed, with its reason), the
solver's and the planner's steps, and a goal withdrawn by a scripted cancel. The live command
is tests/e2e/test_goal_wait_live.py."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from tools.commands.goal_wait import Follower, doing
from tools.commands.scenario_check import load_checked
from tools.commands.simulate import simulate
from tools.records.run_record import RecordWriter, RunRecord
from tools.records.run_recorders import SimRecorder

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "tests" / "e2e" / "fixtures"


def recorded(tmp_path: Path, scenario_file: Path, cycles: int, extra: str = "") -> RunRecord:
    """The record of `scenario_file` (with `extra` TOML appended) run for `cycles`."""
    if extra:
        text = scenario_file.read_text() + extra
        scenario_file = scenario_file.parent / f"x-{scenario_file.name}"
        scenario_file.write_text(text)
    scenario, _ = load_checked(scenario_file)
    scenario = dataclasses.replace(scenario, run=dataclasses.replace(scenario.run,
                                                                     cycles=cycles))
    path = tmp_path / "record.mcap"
    with RecordWriter(path, "wait-1") as writer:
        simulate(scenario, recorder=SimRecorder(writer, "wait-1"))
    return RunRecord(path)


def followed(rec: RunRecord, follower: Follower, step_s: float = 0.0,
             kinds: tuple[str, ...] = ("intention", "goal-list")) -> list[str]:
    """The lines the follower prints over the record (`now` advancing `step_s` a message)."""
    lines, now = [], 0.0
    for key, r in rec.kinds_of(kinds):
        now += step_s
        if key.endswith("/intention"):
            line = follower.intention(r["env"]["cycle"], r["decision"], now)
            if line is not None:
                lines.append(line)
        else:
            follower.goal_list(r["env"]["cycle"], tuple(r["goals"]))
        if follower.ended:
            break
    return lines


@pytest.fixture(scope="module")
def delivery(tmp_path_factory) -> RunRecord:
    """deliver_ahead.toml with PACKET2 posted at cycle 5, as `teleo goal post` would."""
    folder = tmp_path_factory.mktemp("delivery")
    for name in ("deliver_ahead.toml", "deliver_ahead.tlp"):
        (folder / name).write_text((FIXTURES / name).read_text())
    return recorded(folder, folder / "deliver_ahead.toml", 700, '\n[[goals]]\ngoal = '
                    '"(package-delivered PACKET2)"\npriority = 3\nat_cycle = 5\n')


def test_a_delivery_is_followed_to_achieved_at_the_cycle_the_record_gives(delivery):
    follower = Follower("g2", 5)
    lines = followed(delivery, follower)
    achieved = [c["cycle"] for c in delivery.goal_history()["ME"]["g2"]
                if c["status"] == "satisfied"][0]
    assert follower.ended == "achieved" and follower.cycle == achieved
    # `now` stands still: one line per status change only, the path when it became active
    assert [line.split()[2] for line in lines] == ["pending", "active", "achieved"]
    assert lines[0].split(None, 3)[3] == "waits: g1 comes first"
    assert "package-delivered#" in lines[1] and "deliver_ahead.tlp:" in lines[1]
    assert "=> (*gas" in lines[1]
    assert lines[2] == f"cycle {achieved:>6}  achieved"


def test_a_path_that_changes_is_told_at_most_once_a_feedback_period(delivery):
    every = followed(delivery, Follower("g2", 5), step_s=10.0)   # 10 s between messages
    statuses = [line.split()[2] for line in every]
    assert statuses[0] == "pending" and statuses[-1] == "achieved"
    skills = {line.split()[3] for line in every if line.split()[2] == "active"}
    assert len(skills) >= 2 and all(s.startswith("package-delivered#") for s in skills)
    assert len(every) > 3   # the creeping car switches between gas and coasting


def test_a_goal_the_solver_gives_up_fails_with_its_reason(tmp_path):
    scenario = tmp_path / "solver.toml"
    scenario.write_text((FIXTURES / "hold_speed.toml").read_text().replace(
        "solver = false", "solver = true"))
    (tmp_path / "hold_speed.tlp").write_text((FIXTURES / "hold_speed.tlp").read_text())
    follower = Follower("g1", 0)
    lines = followed(recorded(tmp_path, scenario, 10), follower)
    assert follower.ended == "failed"
    assert lines == ["cycle      0  pending    waits: p1 comes first",
                     f"cycle {follower.cycle:>6}  failed"]   # the reason is said at the end
    assert follower.reason.startswith("(package-delivered PACKET1) cannot be achieved: "
                                      "nothing to chain off")


def test_the_solvers_step_is_told_while_it_works(tmp_path):
    rec = recorded(tmp_path, ROOT / "scenarios" / "blocks_figure3.toml", 10)
    decision = rec.by_cycle("intention")[0]["decision"]
    key, text = doing(decision, "g1")
    assert text.startswith("problem solving: (unstackable B A) <- ") and text.endswith(
        "(depth 2)")
    lines = followed(rec, Follower("g1", 0), kinds=("intention",))
    assert lines[0].split()[2:4] == ["impasse", "problem"]
    assert [line.split()[2] for line in lines][1:] == ["active", "achieved"]


def test_the_planners_step_is_told(tmp_path):
    rec = recorded(tmp_path, ROOT / "scenarios" / "office_figure6.toml", 90)
    texts = {doing(r["decision"], "g2")[1] for r in rec.by_cycle("intention").values()}
    assert any(t.startswith("planner: tail-plan <goto-pickup-loc jhm r-5311>") for t in texts)
    assert any(t.startswith("<goto-pickup-loc mitchell r-5303> (programs/office_rogue.tlp:")
               for t in {doing(r["decision"], "g1")[1]
                         for r in rec.by_cycle("intention").values()})


def test_a_goal_that_leaves_the_goal_list_was_withdrawn(tmp_path):
    scenario = tmp_path / "cancel.toml"
    scenario.write_text((FIXTURES / "hold_speed.toml").read_text() + '\n[[goals]]\nop = '
                        '"cancel"\ngoal_id = "g1"\nat_cycle = 12\n')
    (tmp_path / "hold_speed.tlp").write_text((FIXTURES / "hold_speed.tlp").read_text())
    follower = Follower("g1", 0)
    lines = followed(recorded(tmp_path, scenario, 20), follower)
    assert follower.ended == "withdrawn" and follower.cycle == 12
    assert [line.split(None, 3)[2:] for line in lines] == [
        ["pending", "waits: p1 comes first"], ["impasse", "no executable skill path"]]
    assert not Follower("g1", 13).goal_list(12, ())   # a list from before the post


def test_a_failed_goal_that_left_the_list_before_a_decision_said_so_still_ends_in_its_line(
        capsys):
    """Under load the goal list without the goal can come before the decision saying it
    failed: the goal-entry process's record gives the verdict, and the line is printed as a
    decision's would be (a script reads the last line's status)."""
    from types import SimpleNamespace

    from tools.commands.goal_wait import _withdrawn

    follower = Follower("g1", 3)
    assert follower.goal_list(40, ())
    record = {"id": "g1", "status": "failed", "updated_cycle": 39, "note": "nothing to chain off"}
    _withdrawn(follower, "ME", lambda *a: SimpleNamespace(goals=[record]))
    assert (follower.ended, follower.cycle, follower.reason) == \
        ("failed", 39, "nothing to chain off")
    assert capsys.readouterr().out.splitlines()[-1].split() == ["cycle", "39", "failed"]


def test_two_goals_taking_turns_are_told_once_then_counted(tmp_path):
    """Issue 31 (N7): g10 waited on g7 and g9 in turn, a line at every flip (499 lines in 10
    minutes). A flip back to a line of the last REPEAT_CYCLES cycles is said once, then a
    count every REPEAT_S; what is new after it is told again at once."""
    from tools.commands.goal_wait import REPEAT_S

    def decision(note: str, status: str = "pending") -> dict:
        return {"goals": [{"id": "g10", "status": status, "note": note}]}

    follower, lines = Follower("g10", 0), []
    for cycle in range(600):   # a flip every 2 cycles, 1.5 s a cycle: 900 s
        line = follower.intention(cycle, decision(f"waits: g{7 + 2 * (cycle // 2 % 2)} "
                                                  "comes first"), 1.5 * cycle)
        lines += [line] if line else []
    assert lines[:2] == ["cycle      0  pending    waits: g7 comes first",
                         "cycle      2  pending    waits: g9 comes first"]
    assert lines[2].startswith("cycle      4  pending    waits: g7 comes first  [back to a "
                               "line of the last 20 cycles")
    assert len(lines) <= 3 + 900 / REPEAT_S and "changes since cycle 4]" in lines[-1]
    assert follower.intention(600, decision("", "active"), 900.0) == "cycle    600  active"


def test_numbers_in_the_actions_have_three_decimals():
    """Issue 31 (N7): `(*steer -0.05759999999999926)`."""
    told = doing({"goal_id": "g1", "path": [{"skill": "s#1", "where": "x.tlp:1:1"}],
                  "actions": [["*gas", 60], ["*steer", -0.05759999999999926]]}, "g1")[1]
    assert told == "s#1 (x.tlp:1:1) => (*gas 60) (*steer -0.058)"
