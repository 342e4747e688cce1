"""The robot's high-level operations (seed 003 §4-5: acquire-item, deliver-item, C_say,
C_observe, goto) with every outcome: done, and each failure with its reason."""

from __future__ import annotations

import pytest
from office_helpers import events, office, percept, robot, until_done

AT_MITCHELL = {"robots": [{"agent": "ME", "room": "r-5303"}]}


def _failed(out: dict, text: str) -> bool:
    return out["status"] == "failed" and text in out["reason"]


def test_acquire_takes_the_item_from_the_person_after_the_handover():
    world = office(AT_MITCHELL)
    cycles, out = until_done(world, ["*acquire", "mail-mitchell", "mitchell"], every_cycle=True)
    assert out == {"action": ["*acquire", "mail-mitchell", "mitchell"], "status": "done",
                   "reason": ""}
    assert cycles == 6                                     # handover 3 s at 0.5 s a cycle
    assert robot(world)["carrying"] == ["mail-mitchell"]
    item = percept(world, "item", "mail-mitchell")
    assert (item["holder"], item["visible"], item["to"]) == ("ME", "T", "r-5313")
    assert percept(world, "robot", "ME")["carrying"] == 1
    assert world.snapshot_dict()["counters"]["ME"]["acquisitions"] == 1
    [taken] = events(world, "acquired")
    assert (taken["item"], taken["source"]) == ("mail-mitchell", "mitchell")


def test_a_running_command_sent_again_continues_without_an_outcome():
    world = office(AT_MITCHELL)
    assert world.apply_actions("ME", [["*acquire", "mail-mitchell", "mitchell"]]) == []
    world.step()
    assert world.apply_actions("ME", [["*acquire", "mail-mitchell", "mitchell"]]) == []
    assert percept(world, "operation", "ME")["started"] == 0


@pytest.mark.parametrize(("command", "reason"), [
    (["*acquire", "letter-9", "mitchell"], "unknown-item: no item 'letter-9'; items: "),
    (["*acquire", "mail-mitchell", "santa"], "unknown: 'santa' is neither a person nor a room"),
    (["*acquire", "fax-jhm", "mitchell"], "item-not-held: mitchell does not have fax-jhm"),
    (["*acquire", "fax-jhm", "jhm"], "person-absent: jhm is not in r-5303"),
    (["*acquire", "coffee-1", "r-5302"], "not-in-room: ME is in r-5303, not in r-5302"),
    (["*deliver", "mail-mitchell", "mitchell"], "item-not-held: ME does not carry mail-mitchell"),
    (["*observe", "r-5310"], "not-at-room: ME is in r-5303: neither in r-5310 nor at its open"),
    (["*observe", "r-9"], "unknown-room: no room 'r-9'"),
    (["*goto", "lobby"], "unknown-room: no room 'lobby'"),
])
def test_an_operation_that_cannot_run_fails_at_once_with_its_reason(command, reason):
    world = office(AT_MITCHELL)
    [out] = world.apply_actions("ME", [command])
    assert out["status"] == "failed"
    assert out["reason"].startswith(f"ME: ({' '.join(command)}): {reason}")


@pytest.mark.parametrize(("action", "reason"), [
    (["*fly", "r-5303"], "unknown action '*fly'; known: *goto *acquire *deliver"),
    (["*goto"], "(*goto) takes 1 argument(s), got 0"),
    (["*acquire", "mail-mitchell"], "(*acquire) takes 2 argument(s), got 1"),
    (["*goto", 5303], "(*goto) takes ids (symbols), got [5303]"),
    (["*say"], "(*say) takes the words to say, got none"),
    (["*stop", "now"], "(*stop) takes no arguments, got 1"),
    (["*goto", True], "arguments must be symbols or numbers"),
    ("goto", "malformed action 'goto'"),
])
def test_a_malformed_command_fails_naming_what_is_wrong(action, reason):
    world = office()
    [out] = world.apply_actions("ME", [action])
    assert out["status"] == "failed" and reason in out["reason"] and "ME" in out["reason"]
    assert robot(world)["operation"] == {}


def test_the_items_owner_walking_away_ends_the_handover():
    world = office(AT_MITCHELL)
    world.apply_actions("ME", [["*acquire", "mail-mitchell", "mitchell"]])
    world.step()
    assert world.inject({"kind": "move", "person": "mitchell", "room": "r-5310"})["status"] == \
        "done"
    world.step()
    [out] = world.apply_actions("ME", [])
    assert _failed(out, "person-left: mitchell is not in r-5303")
    assert robot(world)["carrying"] == []
    assert percept(world, "person", "mitchell")["room"] == "unknown"   # seen gone


def test_a_robot_in_a_corridor_is_not_in_a_room():
    world = office(AT_MITCHELL)
    world.apply_actions("ME", [["*goto", "r-5317"]])
    for _ in range(8):
        world.step()
    assert world.apply_actions("ME", [["*stop"]]) == [
        {"action": ["*goto", "r-5317"], "status": "failed",
         "reason": "ME: (*goto r-5317): stopped: cancelled by (*stop)"},
        {"action": ["*stop"], "status": "done", "reason": ""}]
    assert world.snapshot_dict()["counters"]["ME"]["failures"] == 0   # the agent's choice
    [out] = world.apply_actions("ME", [["*acquire", "mail-mitchell", "mitchell"]])
    assert _failed(out, "not-in-room: ME is in c-south, not in a room with mitchell")


def test_another_body_command_pre_empts_the_running_one():
    world = office(AT_MITCHELL)
    world.apply_actions("ME", [["*goto", "r-5317"]])
    world.step()
    outcomes = world.apply_actions("ME", [["*goto", "r-5301"]])
    assert outcomes == [{"action": ["*goto", "r-5317"], "status": "failed",
                         "reason": "ME: (*goto r-5317): pre-empted: by (*goto r-5301)"}]
    _, out = until_done(world, ["*goto", "r-5301"])
    assert out["status"] == "done" and robot(world)["place"] == "r-5301"


def test_deliver_hands_the_item_to_the_person_or_leaves_it_in_the_room():
    world = office(AT_MITCHELL)
    until_done(world, ["*acquire", "mail-mitchell", "mitchell"])
    until_done(world, ["*goto", "r-5313"])
    cycles, out = until_done(world, ["*deliver", "mail-mitchell", "r-5313"])
    assert out["status"] == "done" and cycles == 6
    assert robot(world)["carrying"] == []
    [given] = events(world, "delivered")
    assert (given["to"], given["room"], given["addressee"]) == ("r-5313", "r-5313", "r-5313")
    until_done(world, ["*acquire", "mail-reid", "khaigh"])
    until_done(world, ["*goto", "r-5315"])
    _, out = until_done(world, ["*deliver", "mail-reid", "reid"])
    assert out["status"] == "done"
    assert percept(world, "item", "mail-reid")["holder"] == "reid"
    assert world.snapshot_dict()["counters"]["ME"]["deliveries"] == 2


def test_deliver_needs_the_person_there():
    world = office(AT_MITCHELL)
    until_done(world, ["*acquire", "mail-mitchell", "mitchell"])
    [out] = world.apply_actions("ME", [["*deliver", "mail-mitchell", "jhm"]])
    assert _failed(out, "person-absent: jhm is not in r-5303")
    [out] = world.apply_actions("ME", [["*deliver", "mail-mitchell", "r-5313"]])
    assert _failed(out, "not-in-room: ME is in r-5303, not in r-5313")


def test_the_robot_carries_no_more_than_its_capacity():
    items = [{"id": f"fax-{k}", "kind": "fax", "holder": "mitchell"} for k in range(3)]
    world = office({**AT_MITCHELL, "capacity": 2, "items": items})
    until_done(world, ["*acquire", "fax-0", "mitchell"])
    until_done(world, ["*acquire", "fax-1", "mitchell"])
    [out] = world.apply_actions("ME", [["*acquire", "fax-2", "mitchell"]])
    assert _failed(out, "full: ME carries 2 items (capacity 2)")
    [out] = world.apply_actions("ME", [["*acquire", "fax-1", "mitchell"]])
    assert _failed(out, "already-held: ME already carries fax-1")


def test_cold_coffee_is_refused_and_a_kitchen_refills_it():
    world = office({"robots": [{"agent": "ME", "room": "r-5302"}]})
    until_done(world, ["*acquire", "coffee-1", "r-5302"])
    assert percept(world, "item", "coffee-1")["cold"] == "NIL"
    until_done(world, ["*goto", "r-5304"])                      # joseph's office, next door
    world.inject({"kind": "cool", "item": "coffee-1", "temperature": 30.0})
    world.step()
    coffee = percept(world, "item", "coffee-1")
    assert coffee["cold"] == "T" and coffee["temp"] < 30.0
    cycles, out = until_done(world, ["*deliver", "coffee-1", "joseph"])
    assert _failed(out, "coffee-cold: joseph refuses coffee-1 at 29.")
    assert out["reason"].endswith(" C (cold below 45 C)")
    until_done(world, ["*goto", "r-5302"])
    _, out = until_done(world, ["*acquire", "coffee-1", "r-5302"])
    assert out["status"] == "done" and percept(world, "item", "coffee-1")["temp"] == 75.0
    until_done(world, ["*goto", "r-5304"])
    _, out = until_done(world, ["*deliver", "coffee-1", "joseph"])
    assert out["status"] == "done"


def test_coffee_cools_by_newtons_law_once_it_leaves_the_kitchen():
    world = office({"robots": [{"agent": "ME", "room": "r-5302"}]})
    for _ in range(20):
        world.step()
    assert percept(world, "item", "coffee-1")["temp"] == 75.0      # on the machine
    until_done(world, ["*acquire", "coffee-1", "r-5302"])
    start = world.time                                             # taken off the machine now
    while percept(world, "item", "coffee-1")["cold"] == "NIL":
        world.step()
        world.apply_actions("ME", [])
    assert world.time - start == pytest.approx(300 * 0.8109, abs=1.0)   # tau ln(54 / 24)
    assert events(world, "coffee-cold")[0]["agent"] == "ME"


def test_observe_reports_occupied_or_empty():
    world = office({"robots": [{"agent": "ME", "room": "r-5309"}]})
    cycles, out = until_done(world, ["*observe", "r-5309"])
    assert out["status"] == "done" and cycles == 4                # observe_time 2 s
    obs = percept(world, "observed", "r-5309")
    assert obs["result"] == "occupied"                             # a meeting of 4
    [seen] = events(world, "observed")
    assert seen["result"] == "occupied"
    world.inject({"kind": "occupants", "room": "r-5309", "count": 0})
    until_done(world, ["*observe", "r-5309"])
    assert percept(world, "observed", "r-5309")["result"] == "empty"
    assert world.snapshot_dict()["counters"]["ME"]["observations"] == 2


def test_observe_looks_through_an_open_door_from_the_corridor():
    world = office({"robots": [{"agent": "ME", "room": "r-5309"}]})
    world.inject({"kind": "false-success", "agent": "ME", "mode": "halfway"})
    until_done(world, ["*goto", "r-5313"])                       # stops in c-south, x ~ 37
    assert robot(world)["place"] == "c-south"
    _, out = until_done(world, ["*observe", "r-5311"])
    assert out["status"] == "done" and percept(world, "observed", "r-5311")["result"] == \
        "occupied"                                               # jhm
    world.inject({"kind": "close", "door": "d-5311"})
    [out] = world.apply_actions("ME", [["*observe", "r-5311"]])
    assert _failed(out, "not-at-room")


def test_say_is_recorded_in_the_events_and_does_not_stop_the_robot():
    world = office()
    outcomes = world.apply_actions("ME", [["*say", "Going", "to", "room", 5309],
                                          ["*goto", "r-5309"]])
    assert outcomes == [{"action": ["*say", "Going", "to", "room", 5309], "status": "done",
                         "reason": ""}]
    world.step()
    [said] = events(world, "say")
    assert (said["agent"], said["text"]) == ("ME", "Going to room 5309")
    world.apply_actions("ME", [["*say", "This room is occupied"]])
    world.step()
    assert events(world, "say")[0]["text"] == "This room is occupied"
    assert percept(world, "operation", "ME")["status"] == "running"
    assert world.snapshot_dict()["counters"]["ME"]["utterances"] == 2


def test_an_unknown_agent_gets_a_failed_outcome_per_action():
    world = office()
    out = world.apply_actions("R2", [["*stop"], ["*goto", "r-5303"]])
    assert [o["status"] for o in out] == ["failed", "failed"]
    assert "unknown agent 'R2'; agents: ['ME']" in out[0]["reason"]
