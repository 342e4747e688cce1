"""The goal store on disk: durable saves with a last good copy, and recovery from each damaged
file of fault drill 3 (F1), which made the goals process crash-loop; the launcher's summary on
those files (F2)."""

from __future__ import annotations

import json
import os
import re
import stat

import pytest

from agents.processes import goal_file
from agents.processes.goal_file import backup_path, open_store, read_store, save
from agents.processes.goal_store import GoalStore, GoalStoreError
from tools.records import summary


def accept_all(agent: str, goal: str, priority: int) -> str:
    return ""


def posted(*goals: str) -> GoalStore:
    store = GoalStore()
    for goal in goals:
        store, _ = store.post("ME", goal, 5, 0, accept_all)
    return store


def good_text() -> str:
    return json.dumps(posted("(package-delivered P1)", "(package-delivered P2)").to_json())


# The drill's cases (d3_goals.py corrupt --case ...), written over goals.json.
DAMAGED = {
    "truncated": lambda: good_text()[: len(good_text()) // 2],
    "empty": lambda: "",
    "random-bytes": lambda: bytes(range(256)) * 4,
    "json-list": lambda: "[]",
    "json-null": lambda: "null",
    "goal-not-object": lambda: '{"version": 1, "goals": [1]}',
    "bad-status": lambda: good_text().replace('"pending"', '"flying"', 1),
    "deep": lambda: "[" * 100_000,
}
WHAT = {
    "truncated": "not valid JSON at 1:[0-9]+: bad JSON", "empty": "the file is empty",
    "random-bytes": r"not UTF-8 text \(byte 0x80 at offset 128\)",
    "json-list": "expected an object", "json-null": "got null",
    "goal-not-object": r"goals\[0\]: expected an object, got int",
    "bad-status": "status 'flying' is not one of",
    "deep": "not valid JSON at 1:65: nested deeper than 64 levels",
}


def write(path, content) -> None:
    path.write_bytes(content if isinstance(content, bytes) else content.encode())


def test_a_save_writes_the_file_and_its_copy_and_fsyncs_both_and_the_folder(tmp_path,
                                                                              monkeypatch):
    synced = []
    real_fsync = os.fsync

    def spy(fd: int) -> None:  # the real fsync, noting what kind of file it was given
        synced.append(stat.S_ISDIR(os.fstat(fd).st_mode))
        real_fsync(fd)

    monkeypatch.setattr(goal_file.os, "fsync", spy)
    path = tmp_path / "goals.json"
    store = posted("(package-delivered P1)")
    save(store, path)
    assert synced == [False, True, False, True]  # file, folder; copy, folder
    assert path.read_text() == backup_path(path).read_text()
    assert read_store(path) == store and not list(tmp_path.glob("*.tmp"))


@pytest.mark.parametrize("case", sorted(DAMAGED))
def test_a_damaged_store_is_moved_aside_and_recovered_from_its_copy(tmp_path, case):
    path = tmp_path / "goals.json"
    store = posted("(package-delivered P1)", "(package-delivered P2)")
    save(store, path)
    damage = DAMAGED[case]()
    write(path, damage)
    opened = open_store(path)
    assert not opened.lost
    assert [g.goal for g in opened.store.goals] == [g.goal for g in store.goals]
    aside = tmp_path / "goals.json.damaged-1"
    assert aside.read_bytes() == (damage if isinstance(damage, bytes) else damage.encode())
    assert opened.incident.startswith(f"goal store {path}: ")
    assert re.search(WHAT[case], opened.incident), opened.incident
    assert opened.incident.endswith(f"moved aside to goals.json.damaged-1; recovered 2 goal(s) "
                                    f"from {backup_path(path)}")
    # the recovered store is saved again, with the incident for the run's summary
    again = open_store(path)
    assert again.incident == "" and again.store.incidents == (opened.incident,)


def test_with_no_good_copy_the_loss_is_said_and_the_run_goes_on(tmp_path):
    path = tmp_path / "goals.json"
    save(posted("(package-delivered P1)"), path)
    write(path, "[]")
    write(backup_path(path), "")
    opened = open_store(path)
    assert opened.lost and opened.store.goals == ()
    assert opened.incident.startswith(f"GOALS LOST: goal store {path}: expected an object")
    assert "NOTHING RECOVERED: the goals users posted are lost" in opened.incident
    assert (tmp_path / "goals.json.damaged-1").read_text() == "[]"
    assert (tmp_path / "goals.json.bak.damaged-1").exists()
    assert read_store(path).incidents == (opened.incident,)  # kept for the summary
    base = {"run": "r", "scenario": "s", "mode": "lockstep", "seed": 1, "cycles_requested": 0}
    assert summary.build(tmp_path, base, {})["goals_lost"]


def test_a_missing_store_with_a_copy_is_recovered_and_a_new_run_starts_empty(tmp_path):
    path = tmp_path / "goals.json"
    assert open_store(path) == goal_file.Opened(GoalStore())
    save(posted("(package-delivered P1)"), path)
    path.unlink()
    opened = open_store(path)
    assert "missing although its copy goals.json.bak exists" in opened.incident
    assert len(opened.store.goals) == 1 and not opened.lost


def test_damaged_files_are_numbered_and_never_overwritten(tmp_path):
    path = tmp_path / "goals.json"
    save(posted("(package-delivered P1)"), path)
    for n in (1, 2):
        write(path, f"damage {n}")
        open_store(path)
    assert (tmp_path / "goals.json.damaged-2").read_text() == "damage 2"


def test_read_store_says_what_is_wrong(tmp_path):
    with pytest.raises(GoalStoreError, match="cannot read it"):
        read_store(tmp_path / "absent.json")


# -- the launcher's summary on any goals.json (drill F2) -----------------------------------

@pytest.mark.parametrize("case", sorted(DAMAGED))
def test_the_summary_survives_any_goals_file(tmp_path, case, capsys):
    write(tmp_path / summary.GOALS_FILE, DAMAGED[case]())
    base = {"run": "r", "scenario": "s", "mode": "lockstep", "seed": 1, "cycles_requested": 0}
    result = summary.build(tmp_path, base, {})
    summary.echo(result)
    assert result["goals_achieved"] == 0
    json.dumps(result)  # still JSON-able for --summary
    assert "goals achieved: 0 of" in capsys.readouterr().out


def test_the_summary_shows_what_recovery_did(tmp_path, capsys):
    path = tmp_path / summary.GOALS_FILE
    save(posted("(package-delivered P1)"), path)
    write(path, '{"version": 1, "goals": [1]}')
    opened = open_store(path)
    base = {"run": "r", "scenario": "s", "mode": "lockstep", "seed": 1, "cycles_requested": 0}
    result = summary.build(tmp_path, base, {})
    summary.echo(result)
    assert result["goal_store_incidents"] == [opened.incident] and not result["goals_lost"]
    out = capsys.readouterr().out
    assert f"GOAL STORE: {opened.incident}" in out
    assert "g1 ME (package-delivered P1) p5: pending" in out
