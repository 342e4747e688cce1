"""A law that cannot be kept still blocks the goals after it (issue 22; seed 000, "Adding Goal
Priorities": "the agent considers a goal only when all more important goals are satisfied, so
that they always hold during execution of low-priority tasks"). With the goals (door-open D1)
then (lit L1) and no way to open the door, the solver gives (door-open D1) up, and (*switch-on
L1) is never sent; the failed law is looked at again every cycle and acts as soon as a skill
path for it is executable. `teleo step --json` says `impasse` while the solver works and
`failed` once it gave up; the lamp waits in both. On main the lamp was switched on at once."""

from __future__ import annotations

import json

from click.testing import CliRunner

from agents.lang import Engine, GoalStatus, load_program_text
from tools.cli import cli

LAWS = """
(concepts
  ((door-open ?d) :percepts ((door ?d status open)))
  ((unlocked ?d) :percepts ((door ?d lock off)))
  ((lit ?l) :percepts ((lamp ?l status on))))
(skills
  ((door-open ?d) :percepts ((door ?d)) :start ((unlocked ?d)) :actions ((*open ?d)))
  ((lit ?l) :percepts ((lamp ?l)) :actions ((*switch-on ?l))))
(goals
  (door-open D1)
  (lit L1))
"""
LOCKED = [["door", "D1", "status", "shut", "lock", "on"], ["lamp", "L1", "status", "off"]]
UNLOCKED = [["door", "D1", "status", "shut", "lock", "off"], ["lamp", "L1", "status", "off"]]
OPEN = [["door", "D1", "status", "open", "lock", "off"], ["lamp", "L1", "status", "off"]]


def _trace(worlds: list[list]) -> list[tuple]:
    engine = Engine(load_program_text(LAWS, "laws.tlp"))
    state, out = engine.initial_state(), []
    for percepts in worlds:
        result = engine.cycle(state, percepts)
        state = result.state
        d = result.decision
        out.append((d.status_of("p1"), d.status_of("p2"),
                    [a.to_list() for a in d.actions], d.goals[1].note))
    return out


def test_a_failed_law_blocks_the_goals_after_it_and_acts_again_when_it_can():
    trace = _trace([LOCKED] * 4 + [UNLOCKED, OPEN])
    assert [t[:3] for t in trace] == [
        (GoalStatus.IMPASSE, GoalStatus.PENDING, []),    # pushed (unlocked D1)
        (GoalStatus.FAILED, GoalStatus.PENDING, []),     # nothing achieves (unlocked D1)
        (GoalStatus.FAILED, GoalStatus.PENDING, []),     # looked at again: still no path
        (GoalStatus.FAILED, GoalStatus.PENDING, []),
        (GoalStatus.ACTIVE, GoalStatus.PENDING, [["*open", "D1"]]),   # a path again: acts
        (GoalStatus.SATISFIED, GoalStatus.ACTIVE, [["*switch-on", "L1"]])]
    assert {t[3] for t in trace[:5]} == {"waits: p1 comes first"}


def test_no_skill_at_all_for_the_law_fails_it_at_once_and_the_lamp_still_waits():
    no_door = LAWS.replace("((door-open ?d) :percepts ((door ?d)) :start ((unlocked ?d)) "
                           ":actions ((*open ?d)))", "")
    engine = Engine(load_program_text(no_door, "laws.tlp"))
    state = engine.initial_state()
    for _ in range(3):
        result = engine.cycle(state, LOCKED)
        state = result.state
        assert result.decision.status_of("p1") is GoalStatus.FAILED
        assert result.decision.status_of("p2") is GoalStatus.PENDING
        assert result.decision.actions == ()
    assert state.failure_of("p1").startswith("(door-open D1) cannot be achieved: nothing to "
                                             "chain off: no primitive skill achieves door-open")


def test_teleo_step_says_impasse_then_failed_and_the_lamp_waits(tmp_path):
    program, seen = tmp_path / "laws.tlp", tmp_path / "locked.json"
    program.write_text(LAWS)
    seen.write_text(json.dumps(LOCKED))
    state = tmp_path / "state.json"
    runner, out = CliRunner(), []
    for k in range(2):
        args = ["step", str(program), "--percepts", str(seen), "--json", "--save-state",
                str(state)] + (["--state", str(state)] if k else [])
        done = runner.invoke(cli, args)
        assert done.exit_code == 0, done.output
        decision = json.loads(done.output)["decision"]
        out.append(([(g["id"], g["status"]) for g in decision["goals"]], decision["actions"]))
    assert out == [([("p1", "impasse"), ("p2", "pending")], []),
                   ([("p1", "failed"), ("p2", "pending")], [])]
