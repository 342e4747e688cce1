"""The executive's goal bookkeeping with the real engine: the goal list it receives each
cycle is the truth, so posts, cancels and priority changes reach the engine."""

from __future__ import annotations

import logging
from pathlib import Path

from agents.lang import Engine, load_program
from agents.processes.executive import EngineHost

PROGRAM = Path(__file__).resolve().parents[1] / "e2e" / "fixtures" / "hold_speed.tlp"
SLOW = (["self", "ME", "speed", 0.0, "limit", 15],)
CRUISING = (["self", "ME", "speed", 8.0, "limit", 15],)


def entry(goal_id: str, goal: str, priority: int) -> dict:
    return {"id": goal_id, "goal": goal, "priority": priority, "status": "pending"}


def step(executive: EngineHost, percepts) -> dict:
    beliefs = tuple(b.to_list() for b in executive.engine.infer(percepts))
    return executive.decide(percepts, beliefs).to_dict()


def test_goal_list_changes_reach_the_engine():
    executive = EngineHost(Engine(load_program(str(PROGRAM))), logging.getLogger("test"))
    executive.sync_goals((entry("g1", "(package-delivered PACKET1)", 3),
                          entry("g2", "(package-delivered PACKET2)", 5)))
    decision = step(executive, SLOW)
    assert [g["id"] for g in decision["goals"]] == ["p1", "g1", "g2"]
    assert decision["actions"] == [["*gas", 10]]  # the law first: too slow
    executive.sync_goals((entry("g2", "(package-delivered PACKET2)", 2),))  # g1 cancelled
    decision = step(executive, CRUISING)
    assert [(g["id"], g["priority"]) for g in decision["goals"]] == [("p1", 1), ("g2", 2)]
    assert decision["goals"][0]["status"] == "satisfied"


def test_a_goal_the_engine_refuses_is_skipped_not_fatal():
    executive = EngineHost(Engine(load_program(str(PROGRAM))), logging.getLogger("test"))
    executive.sync_goals((entry("g1", "(flying ME)", 3),))
    executive.sync_goals((entry("g1", "(flying ME)", 3),))
    assert executive.goals.refused == {"g1"}
    assert [g["id"] for g in step(executive, SLOW)["goals"]] == ["p1"]
