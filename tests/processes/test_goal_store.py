"""The goal-entry process's store: validation, statuses mirrored from intentions, persistence."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from agents.processes.goal_file import open_store, save
from agents.processes.goal_store import (
    MAX_KEPT_WITHDRAWN,
    MAX_LIVE_GOALS,
    MAX_PRIORITY,
    GoalState,
    GoalStore,
    GoalStoreError,
)


def load(path):
    """The store a goals process would start with from `path`."""
    return open_store(path).store


def accept_all(agent: str, goal: str, priority: int) -> str:
    return ""


def known_concepts(agent: str, goal: str, priority: int) -> str:
    name = goal.strip("()").split()[0]
    return "" if name == "package-delivered" else f"unknown concept {name}"


def test_post_assigns_ids_in_order_and_starts_pending():
    store, first = GoalStore().post("ME", "(package-delivered  P1)", 3, 0, accept_all)
    store, second = store.post("ME", "(package-delivered P2)", 2, 5, accept_all)
    assert (first.id, second.id) == ("g1", "g2")
    assert first.goal == "(package-delivered P1)"  # whitespace normalised
    assert store.goal_list("ME") == (
        {"id": "g1", "goal": "(package-delivered P1)", "priority": 3, "status": "pending"},
        {"id": "g2", "goal": "(package-delivered P2)", "priority": 2, "status": "pending"},
    )


def test_refused_goal_names_the_reason_and_is_not_stored():
    with pytest.raises(GoalStoreError, match="unknown concept flying"):
        GoalStore().post("ME", "(flying ME)", 1, 0, known_concepts)
    with pytest.raises(GoalStoreError, match=r"priority must be an integer in 1\.\.1000000"):
        GoalStore().post("ME", "(package-delivered P1)", 0, 0, accept_all)


def test_duplicate_of_a_live_goal_is_refused():
    store, _ = GoalStore().post("ME", "(package-delivered P1)", 3, 0, accept_all)
    with pytest.raises(GoalStoreError, match="already posted for ME as g1"):
        store.post("ME", "(package-delivered P1)", 3, 0, accept_all)
    # another agent may want the same thing
    store.post("OTHER", "(package-delivered P1)", 3, 0, accept_all)


def test_statuses_follow_the_executive_and_cancel_withdraws():
    store, _ = GoalStore().post("ME", "(package-delivered P1)", 3, 0, accept_all)
    store, _ = store.post("ME", "(package-delivered P2)", 4, 0, accept_all)
    decision = {"goals": [{"id": "law1", "status": "satisfied"},
                          {"id": "g1", "status": "active"},
                          {"id": "g2", "status": "suspended"}]}
    store = store.update_from_intention("ME", decision, 7)
    assert [g.status for g in store.goals] == [GoalState.ACTIVE, GoalState.SUSPENDED]
    store = store.update_from_intention("ME", {"goals": [{"id": "g1", "status": "satisfied"}]}, 9)
    assert store.get("g1").status is GoalState.ACHIEVED and store.get("g1").updated_cycle == 9
    store = store.cancel("g2", 10)
    assert [g["id"] for g in store.goal_list("ME")] == ["g1"]
    # a cancelled goal stays cancelled whatever the executive still reports
    store = store.update_from_intention("ME", {"goals": [{"id": "g2", "status": "active"}]}, 11)
    assert store.get("g2").status is GoalState.CANCELLED


def test_priority_changes_and_unknown_ids_are_explained():
    store, _ = GoalStore().post("ME", "(package-delivered P1)", 3, 0, accept_all)
    assert store.set_priority("g1", 1, 2).get("g1").priority == 1
    with pytest.raises(GoalStoreError, match="no goal 'g9'"):
        store.cancel("g9", 0)


def test_save_and_load_round_trip(tmp_path):
    store, _ = GoalStore().post("ME", "(package-delivered P1)", 3, 0, accept_all)
    store = store.mark_scripted([0, 2]).update_from_intention(
        "ME", {"goals": [{"id": "g1", "status": "impasse"}]}, 4)
    path = tmp_path / "goals.json"
    save(store, path)
    assert load(path) == store
    assert load(tmp_path / "absent.json") == GoalStore()


ops = st.lists(st.tuples(st.sampled_from(["post", "cancel", "priority", "report"]),
                         st.integers(1, 5), st.sampled_from(["satisfied", "active", "pending"])),
               max_size=30)


@given(ops)
def test_any_history_survives_a_restart(history):
    """Property: whatever happened, saving and loading gives back exactly the same goals."""
    import tempfile
    from pathlib import Path

    store = GoalStore()
    for op, n, status in history:
        try:
            if op == "post":
                store, _ = store.post("ME", f"(package-delivered P{n})", n, 0, accept_all)
            elif op == "cancel":
                store = store.cancel(f"g{n}", 1)
            elif op == "priority":
                store = store.set_priority(f"g{n}", n, 1)
            else:
                store = store.update_from_intention("ME", {"goals": [{"id": f"g{n}",
                                                                       "status": status}]}, 2)
        except GoalStoreError:
            pass
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "goals.json"
        save(store, path)
        assert load(path) == store
    ids = [g.id for g in store.goals]
    assert len(ids) == len(set(ids))


def test_impasse_and_failure_are_reported_as_they_are_with_the_engines_note():
    store, _ = GoalStore().post("ME", "(clear A)", 3, 0, accept_all)
    store = store.update_from_intention("ME", {"goals": [
        {"id": "g1", "status": "impasse", "note": "no executable skill path"}]}, 4)
    assert (store.get("g1").status, store.get("g1").note) == (GoalState.IMPASSE,
                                                               "no executable skill path")
    store = store.update_from_intention("ME", {"goals": [
        {"id": "g1", "status": "failed", "note": "every alternative failed"}]}, 9)
    assert (store.get("g1").status, store.get("g1").note) == (GoalState.FAILED,
                                                               "every alternative failed")
    assert store.goal_list("ME") == ()     # a failed goal is no longer pursued


# -- bounds on requests (fault drill O5) ---------------------------------------------------

def test_a_goal_over_the_length_limit_is_refused_before_it_is_read():
    with pytest.raises(GoalStoreError, match=r"longer than 65536 characters"):
        GoalStore().post("ME", "(package-delivered " + "X" * 1_000_000 + ")", 5, 0, accept_all)


@pytest.mark.parametrize("priority", [0, -3, MAX_PRIORITY + 1, 2**64 - 1])
def test_priorities_outside_the_range_are_refused(priority):
    in_range = rf"priority must be an integer in 1\.\.{MAX_PRIORITY}"
    with pytest.raises(GoalStoreError, match=in_range):
        GoalStore().post("ME", "(package-delivered P1)", priority, 0, accept_all)
    store, _ = GoalStore().post("ME", "(package-delivered P1)", MAX_PRIORITY, 0, accept_all)
    with pytest.raises(GoalStoreError, match="priority must be"):
        store.set_priority("g1", priority, 1)


def test_live_goals_per_agent_are_bounded_and_a_cancel_frees_a_place():
    store = GoalStore()
    for n in range(MAX_LIVE_GOALS):
        store, _ = store.post("ME", f"(package-delivered P{n})", 5, 0, accept_all)
    with pytest.raises(GoalStoreError, match=f"ME has {MAX_LIVE_GOALS} live goals, the limit"):
        store.post("ME", "(package-delivered EXTRA)", 5, 0, accept_all)
    store.post("OTHER", "(package-delivered EXTRA)", 5, 0, accept_all)  # per agent
    store = store.cancel("g1", 1)
    store, record = store.post("ME", "(package-delivered EXTRA)", 5, 0, accept_all)
    assert record.id == f"g{MAX_LIVE_GOALS + 1}"


def test_an_achieved_goal_frees_a_place():
    store = GoalStore()
    for n in range(MAX_LIVE_GOALS):
        store, _ = store.post("ME", f"(package-delivered P{n})", 5, 0, accept_all)
    decision = {"goals": [{"id": "g3", "status": "satisfied"}]}
    store = store.update_from_intention("ME", decision, 7)
    store, record = store.post("ME", "(package-delivered EXTRA)", 5, 8, accept_all)
    assert record.id == f"g{MAX_LIVE_GOALS + 1}" and store.get("g3").status.value == "achieved"
    with pytest.raises(GoalStoreError, match=f"ME has {MAX_LIVE_GOALS} live goals, the limit"):
        store.post("ME", "(package-delivered MORE)", 5, 8, accept_all)


def test_only_the_latest_withdrawn_goals_are_kept():
    store = GoalStore()
    for n in range(MAX_KEPT_WITHDRAWN + 5):
        store, record = store.post("ME", f"(package-delivered P{n})", 5, 0, accept_all)
        store = store.cancel(record.id, n)
    ids = [g.id for g in store.goals]
    assert len(ids) == MAX_KEPT_WITHDRAWN and ids[0] == "g6"
    assert store.next_id == MAX_KEPT_WITHDRAWN + 6  # ids are never given twice


@pytest.mark.parametrize("doc, message", [
    ([], "expected an object"),
    (None, "expected an object .* got null"),
    ({"version": 1, "goals": [1]}, r"goals\[0\]: expected an object, got int"),
    ({"version": 1, "goals": {}}, r"store.goals: expected list, got \{\}"),
    ({"version": 2, "goals": []}, "version: expected 1, got 2"),
    ({"version": 1, "goals": [{"id": "g1", "agent": "ME", "goal": "(x)", "priority": 1,
                               "status": "flying"}]}, r"goals\[0\]: status 'flying' is not one"),
    ({"version": 1, "goals": [{"id": "g1", "agent": "ME", "goal": "(x)", "priority": "1",
                               "status": "active"}]}, r"goals\[0\].priority: expected int"),
    ({"version": 1, "next_id": 1, "goals": [{"id": "g1", "agent": "ME", "goal": "(x)",
                                             "priority": 1, "status": "active"}]},
     "next_id 1 would give an id already used"),
])
def test_a_store_of_the_wrong_shape_says_what_is_wrong(doc, message):
    with pytest.raises(GoalStoreError, match=message):
        GoalStore.from_json(doc)
