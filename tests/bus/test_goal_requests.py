"""The goal-entry process as a real process on the bus: it recovers a damaged store instead of
crash-looping (fault drill F1), and it bounds and rate-limits goal requests (drill 4d, O5)."""

from __future__ import annotations

import json
import signal
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import replace
from pathlib import Path

from bus_helpers import ROOT, python

from agents.processes.goal_file import backup_path, save
from agents.processes.goal_store import GoalStore
from bus import keys
from bus.messages import GoalReply, GoalRequest
from bus.node import Node, open_node

SCENARIO = ROOT / "tests" / "e2e" / "fixtures" / "hold_speed.toml"  # one agent, ME


@contextmanager
def goals_process(cfg, run: str, store: Path) -> Iterator[tuple[Node, subprocess.Popen, Path]]:
    """The goals process of `run` on `store`, announced; stopped with SIGINT at the end."""
    log = store.parent / "goals.log"
    with open(log, "w") as out:
        proc = python("-m", "agents.processes.goals", "--run", run, "--scenario", str(SCENARIO),
                      "--store", str(store), *cfg.to_args(), stdout=out,
                      stderr=subprocess.STDOUT)
    try:
        with open_node(cfg, run, "test") as node:
            assert node.presence.wait_for(lambda alive: "goals" in alive, 60), log.read_text()
            yield node, proc, log
    finally:
        proc.send_signal(signal.SIGINT)
        assert proc.wait(30) == 0, log.read_text()


def ask(node: Node, op: str, goal: str = "", priority: int = 0, goal_id: str = "",
        sender: str = "test") -> GoalReply:
    env = replace(node.envelope(), sender=sender)
    request = GoalRequest(env, op, "ME", goal, priority, goal_id)
    return node.query(keys.goals(node.run, "ME"), request, 10.0)


def user_goals(goals: tuple) -> list[tuple[str, str]]:
    return [(g["id"], g["goal"]) for g in goals]


def test_a_damaged_store_is_recovered_and_the_process_keeps_serving(cfg, run_id, tmp_path):
    store = tmp_path / "goals.json"
    save(GoalStore().post("ME", "(package-delivered PACKET1)", 3, 0, lambda *a: "")[0], store)
    store.write_text('{"version": 1, "goals": [1]}')  # drill case goal-not-object
    with goals_process(cfg, run_id, store) as (node, proc, log):
        reply = ask(node, "list")
        assert reply.ok and user_goals(reply.goals) == [("g1", "(package-delivered PACKET1)")]
        assert proc.poll() is None
    text = log.read_text()
    assert (f"goal store {store}: goals[0]: expected an object, got int; moved aside to "
            f"goals.json.damaged-1; recovered 1 goal(s) from {backup_path(store)}") in text
    assert "Traceback" not in text
    assert (tmp_path / "goals.json.damaged-1").read_text() == '{"version": 1, "goals": [1]}'


def test_with_nothing_to_recover_the_loss_is_logged_and_posts_still_work(cfg, run_id, tmp_path):
    store = tmp_path / "goals.json"
    store.write_text("[]")
    backup_path(store).write_bytes(b"\x00\xff" * 10)
    with goals_process(cfg, run_id, store) as (node, _proc, log):
        assert user_goals(ask(node, "list").goals) == []
        posted = ask(node, "post", "(package-delivered PACKET1)", 4)
        assert posted.ok, posted.reason
    assert "ERROR GOALS LOST: goal store" in log.read_text()
    doc = json.loads(store.read_text())
    assert "NOTHING RECOVERED" in doc["incidents"][0]  # for the run's summary
    assert [g["goal"] for g in doc["goals"]] == ["(package-delivered PACKET1)"]


def test_requests_are_bounded_saved_before_the_answer_and_rate_limited(cfg, run_id, tmp_path):
    store = tmp_path / "goals.json"
    with goals_process(cfg, run_id, store) as (node, _proc, _log):
        huge = ask(node, "post", "(package-delivered " + "X" * 1_000_000 + ")", 5)
        assert not huge.ok and huge.reason.endswith("longer than 65536 characters")
        big_priority = ask(node, "post", "(package-delivered PACKET1)", 2**64 - 1)
        assert not big_priority.ok and "priority must be an integer in 1..1000000" in \
            big_priority.reason
        posted = ask(node, "post", "(package-delivered PACKET1)", 7)
        assert posted.ok, posted.reason
        # durable before the answer: the file already holds the goal
        assert [g["goal"] for g in json.loads(store.read_text())["goals"]] == [
            "(package-delivered PACKET1)"]
        flood = [ask(node, "list", sender="flood") for _ in range(60)]
        refused = [r.reason for r in flood if not r.ok]
        assert len(refused) >= 5
        assert refused[0].startswith("too many requests from client 'flood': at most 20 at once")
        assert ask(node, "list", sender="calm").ok  # another client is still served
        junk = list(node.session.get(keys.goals(run_id, "ME"), payload=b"\xc1" * 7, timeout=10))
        assert junk and junk[0].err is not None
