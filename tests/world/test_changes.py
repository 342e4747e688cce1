"""What a running launch lets change (world/changes.py): the world's check of a `teleo set` is
`launch --set`'s, a key read only at the start is refused by name, and the changes due at a
cycle become its WorldState.control, applied in order."""

from __future__ import annotations

from pathlib import Path

from world.changes import Changes
from world.run_scenario import load_scenario

HOLD_SPEED = Path(__file__).parent.parent / "e2e" / "fixtures" / "hold_speed.toml"


class _Clock:
    period_s = 0.2


class _Rec:
    def __init__(self) -> None:
        self.render_every, self.events = 10, []

    def event(self, kind: str, **fields) -> None:
        self.events.append((kind, fields))


def test_a_set_is_checked_as_launch_set_and_a_fixed_key_refused_by_name():
    changes = Changes(load_scenario(HOLD_SPEED, ("run.render_every=5",)))
    assert changes.check({"op": "set", "text": "world.pedestrians=4"}).startswith(
        "world.pedestrians cannot change while the run runs (it is read when the run starts: "
        "relaunch with --set world.pedestrians=...)")
    wrong = changes.check({"op": "set", "text": "run.deadline=-1"})
    assert wrong == "run.deadline=-1: [run].deadline: expected > 0 [s], got -1"
    assert "\n" not in wrong
    event = {"op": "set", "text": "run.deadline=0.5"}
    assert changes.check(event) == "" and (event["key"], event["value"]) == ("run.deadline", 0.5)
    assert changes.check({"op": "set", "text": "nokey"}).startswith(
        "--set nokey: expected KEY=VALUE")


def test_a_program_for_an_agent_of_the_run_only():
    changes = Changes(load_scenario(HOLD_SPEED))
    assert changes.check({"op": "load", "agent": "YOU", "name": "x", "text": ""}) == \
        "no agent 'YOU' in this run; agents: ME"
    assert changes.check({"op": "load", "agent": "ME", "name": "x", "text": 3}) != ""
    assert changes.check({"op": "load", "agent": "ME", "name": "x.tlp", "text": "(goals)"}) == ""


def test_the_changes_due_at_a_cycle_are_its_control_applied_in_order():
    changes, clock, rec = Changes(load_scenario(HOLD_SPEED)), _Clock(), _Rec()
    due = []
    for e in ({"op": "set", "text": "run.render_every=20"},
              {"op": "load", "agent": "ME", "name": "a.tlp", "text": "A"},
              {"op": "load", "agent": "ME", "name": "b.tlp", "text": "B"},
              {"op": "set", "text": "run.deadline=0.05"}):
        assert changes.check(e) == ""
        due.append(e)
    control = changes.at_cycle(due, clock, rec, 7)
    assert control == {"programs": {"ME": {"name": "b.tlp", "text": "B"}},   # the later wins
                       "set": [{"key": "run.render_every", "value": 20},
                               {"key": "run.deadline", "value": 0.05}]}
    assert (clock.period_s, rec.render_every) == (0.05, 20)
    assert rec.events == [("program", {"cycle": 7, "agent": "ME", "name": "b.tlp"}),
                          ("set", {"cycle": 7, "key": "run.render_every", "value": 20}),
                          ("set", {"cycle": 7, "key": "run.deadline", "value": 0.05})]
    assert changes.scenario.run.render_every == 20   # a later set is checked on top of it
    assert changes.at_cycle([], clock, rec, 8) == {}
