"""A goal's history is told only from what is known (issue 24, item 2; drill N1): a status
change the run record saw only after a gap is dated to the range it lies in, never to the
cycle after the gap, unless the goal store names its cycle; a store that could not be saved
(a full disk) is told apart from the record that saw more. Random runs with random gaps."""

from __future__ import annotations

import json

from hypothesis import given, settings
from hypothesis import strategies as st

from bus import keys
from bus.messages import Envelope, Intention, WorldState
from bus.record import message_record
from tools.records.goal_reports import history_text, reconcile
from tools.records.run_record import (
    RECORD_FILE,
    GoalHistory,
    RecordWriter,
    RunRecord,
)

STATUSES = ("pending", "active", "suspended", "satisfied")


def env(cycle: int) -> Envelope:
    return Envelope(1, "r1", cycle, "t", 99)


def write(path, truth: list[str], lost: set[int]) -> None:
    """A record of len(truth) cycles of goal g1's statuses, lacking the cycles in `lost` (a
    router outage: neither the world state nor the intention of those cycles came)."""
    with RecordWriter(path, "r1") as rec:
        for cycle, status in enumerate(truth):
            if cycle in lost:
                continue
            for key, msg in ((keys.world_state("r1"), WorldState(env(cycle), {"time": cycle},
                                                                 {}, [])),
                             (keys.intention("r1", "ME"), Intention(env(cycle), "ME", {
                                 "goals": [{"id": "g1", "status": status, "priority": 5}]}))):
                rec.add(key, message_record(key, msg))


def change_of(truth: list[str], cycle: int) -> int:
    """The cycle at which the status `truth` shows at `cycle` began."""
    while cycle > 0 and truth[cycle - 1] == truth[cycle]:
        cycle -= 1
    return cycle


runs = st.lists(st.tuples(st.sampled_from(STATUSES), st.integers(1, 30)), min_size=1,
                max_size=12).map(lambda parts: [s for s, n in parts for _ in range(n)])


@settings(max_examples=60, deadline=None)
@given(truth=runs, data=st.data())
def test_every_change_is_dated_exactly_or_to_the_gap_it_lies_in(tmp_path_factory, truth, data):
    n = len(truth)
    lost: set[int] = set()
    for _ in range(data.draw(st.integers(0, 3))):   # up to three outages
        start = data.draw(st.integers(0, n - 1))
        lost |= set(range(start, data.draw(st.integers(start, n))))
    lost -= {n - 1}
    path = tmp_path_factory.mktemp("gaps") / RECORD_FILE
    write(path, truth, lost)
    history = RunRecord(path).goal_history()["ME"]["g1"]
    seen = [c for c in range(n) if c not in lost]
    for entry in history:
        assert truth[entry["cycle"]] == entry["status"]
        began = change_of(truth, entry["cycle"])
        if "after" in entry:
            assert entry["after"] < began <= entry["cycle"], (entry, began)
            assert any(c in lost for c in range(entry["after"] + 1, entry["cycle"]))
        else:
            assert began == entry["cycle"], (entry, began)
    told = {(e["cycle"], e["status"]) for e in history}
    for c in seen:   # every change the record holds both sides of is there, exactly
        if (c == 0 or (c - 1 not in lost and truth[c - 1] != truth[c])):
            assert (c, truth[c]) in told


def test_the_drill_case_the_goal_store_dates_what_the_record_missed(tmp_path) -> None:
    """Drill N1: the record lacked cycles 201-485; g1 was achieved at 216. The record alone
    says "achieved 201..486"; with the goal store (which saw every cycle) "achieved 216"."""
    truth = ["active"] * 216 + ["satisfied"] * 434
    write(tmp_path / RECORD_FILE, truth, set(range(201, 486)))
    changes = RunRecord(tmp_path / RECORD_FILE).goal_history()["ME"]["g1"]
    assert [(c["cycle"], c["status"], c.get("after")) for c in changes] == [
        (0, "active", None), (486, "satisfied", 200)]
    store = {"id": "g1", "agent": "ME", "status": "achieved", "updated_cycle": 216}
    alone = reconcile({**store, "updated_cycle": 0}, changes)["history"]
    assert history_text(alone) == " (active 0, achieved 201..486)"
    told = reconcile(store, changes)
    assert told["history"] == [{"cycle": 0, "status": "active"},
                               {"cycle": 216, "status": "achieved", "source": "goal store"}]
    assert told["status"] == "achieved"


def test_a_record_that_lost_its_end_takes_the_final_status_from_the_store() -> None:
    changes = [{"cycle": 0, "status": "active", "goal": "", "priority": 5, "note": ""}]
    store = {"id": "g1", "agent": "ME", "status": "achieved", "updated_cycle": 517}
    assert reconcile(store, changes)["history"] == [
        {"cycle": 0, "status": "active"},
        {"cycle": 517, "status": "achieved", "source": "goal store"}]


def test_a_store_not_saved_since_takes_its_status_from_the_record() -> None:
    """A full disk: the goal store was last saved with g1 active (cycle 1); the record saw
    it achieved at 216. The summary says achieved, and why it differs from the store."""
    changes = [{"cycle": 1, "status": "active", "goal": "", "priority": 5, "note": ""},
               {"cycle": 216, "status": "satisfied", "goal": "", "priority": 5, "note": ""}]
    store = {"id": "g1", "agent": "ME", "status": "active", "updated_cycle": 1}
    told = reconcile(store, changes)
    assert told["status"] == "achieved" and told["updated_cycle"] == 216
    assert told["note"] == ("from the run record: the goal store was last saved with active "
                            "(cycle 1)")
    assert reconcile({**store, "status": "achieved", "updated_cycle": 216}, changes) == {
        **store, "status": "achieved", "updated_cycle": 216,
        "history": [{"cycle": 1, "status": "active"}, {"cycle": 216, "status": "achieved"}]}


def _arrivals(truth: list[str], end: str, gone: int) -> list[dict]:
    """The intention and goal-list records of goal g1 (and g2, always pending): g1 has the
    statuses `truth`, then `end` ("failed": the executive reports it at cycle `gone` - 1 and
    the goals process drops it from the list of `gone`; "cancelled": a user withdrew it, it
    is missing from the list and the intentions from `gone` on)."""
    out = []
    for cycle in range(gone + 3):
        listed = [{"id": "g2", "goal": "(clear B)", "priority": 5}]
        if cycle < gone:
            listed.append({"id": "g1", "goal": "(clear A)", "priority": 5})
        out.append({"kind": "GoalList", "agent": "ME", "env": {"cycle": cycle},
                    "goals": listed})
        goals = [{"id": "g2", "status": "pending", "goal": "(clear B)", "priority": 5}]
        if cycle < gone:
            status = "failed" if end == "failed" and cycle == gone - 1 else \
                truth[min(cycle, len(truth) - 1)]
            goals.append({"id": "g1", "status": status, "goal": "(clear A)", "priority": 5})
        out.append({"kind": "Intention", "agent": "ME", "env": {"cycle": cycle},
                    "decision": {"goals": goals}})
    return out


def _history(records: list[dict]) -> dict:
    history = GoalHistory()
    for record in records:
        history.feed(record)
    return history.changes["ME"]


@settings(max_examples=80, deadline=None)
@given(truth=runs, end=st.sampled_from(("failed", "cancelled")), data=st.data())
def test_the_history_is_the_same_whatever_order_the_records_arrive_in(truth, end, data):
    """Drills 2026-12-04 D2: the goal list of t+1 arriving before the intention of t that said
    "failed" recorded the goal as cancelled."""
    gone = data.draw(st.integers(1, len(truth)))
    records = _arrivals(truth, end, gone)
    in_order = _history(records)
    arrived = data.draw(st.permutations(records))
    assert _history(arrived) == in_order
    last = in_order["g1"][-1]
    assert (last["status"], last["cycle"]) == (end, gone - 1 if end == "failed" else gone)
    assert [c["status"] for c in in_order["g2"]] == ["pending"]


def test_the_drill_case_a_failure_that_arrives_late_stays_a_failure() -> None:
    def goal_list(cycle, listed):
        return {"kind": "GoalList", "agent": "ME", "env": {"cycle": cycle},
                "goals": [{"id": "g3", "goal": "(p)", "priority": 5}] if listed else []}

    def intention(cycle, status):
        return {"kind": "Intention", "agent": "ME", "env": {"cycle": cycle},
                "decision": {"goals": [{"id": "g3", "status": status, "goal": "(p)"}]}}

    crossed = [goal_list(516, True), goal_list(517, True), intention(516, "pending"),
               goal_list(518, False), intention(517, "failed")]
    assert [(c["cycle"], c["status"]) for c in _history(crossed)["g3"]] == [
        (516, "pending"), (517, "failed")]


def test_a_failure_in_the_goal_store_is_never_overridden_by_the_record() -> None:
    goal = {"id": "g3", "status": "failed", "updated_cycle": 517}
    out = reconcile(goal, [{"cycle": 516, "status": "pending"},
                           {"cycle": 518, "status": "cancelled"}])
    assert out["status"] == "failed"


JUNK = st.recursive(st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=5),
                    lambda inner: st.lists(inner, max_size=4)
                    | st.dictionaries(st.sampled_from(["id", "status", "goal", "priority",
                                                      "note", "goals", "cycle", "x"]), inner,
                                      max_size=5), max_leaves=20)


@settings(max_examples=200, deadline=None)
@given(kind=st.sampled_from(("Intention", "GoalList")), cycle=JUNK | st.integers(0, 9),
       goals=JUNK, decision=JUNK)
def test_a_record_of_any_shape_never_breaks_the_history(kind, cycle, goals, decision) -> None:
    """A hostile peer's intention with a dict for a goal id crashed the launch's recorder
    thread ("unhashable type: 'dict'"), and the record lost the rest of the run."""
    history = GoalHistory()
    history.feed({"kind": kind, "agent": "ME", "env": {"cycle": cycle}, "goals": goals,
                  "decision": decision})
    history.feed({"kind": kind, "agent": "ME", "env": cycle, "goals": [goals],
                  "decision": {"goals": [decision, goals]}})
    json.dumps(history.to_meta())
