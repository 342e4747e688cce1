"""Bringing an engine's user goals in line with a goal list (the goal-entry process's, or the
goal store's in `teleo simulate`): posted goals are added, withdrawn ones dropped and
reprioritised ones moved, in list order. Pure: no bus, so `teleo simulate` shares it with the
executive process and both runs see the same goals the same way."""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Any

from agents.lang import GoalError


@dataclass
class GoalSync:
    """The user goals an engine state already holds (id -> (text, priority)) and the ids the
    engine refused (not offered again)."""

    user: dict[str, tuple[str, int]] = field(default_factory=dict)
    refused: set[str] = field(default_factory=set)

    @classmethod
    def of(cls, state: Any) -> GoalSync:
        """What ``state`` (an EngineState) already holds."""
        return cls({e.id: (e.text, e.priority) for e in state.goals if e.origin == "user"})

    def apply(self, engine: Any, state: Any, goal_list: tuple[dict[str, Any], ...],
              log: logging.Logger) -> Any:
        """The engine state with the user goals of ``goal_list``; a goal the engine refuses
        is logged and left out."""
        wanted = {g["id"]: (g["goal"], int(g["priority"])) for g in goal_list}
        ends = {g["id"]: (bool(g.get("once", False)), g.get("deadline") or None)
                for g in goal_list}
        for goal_id in [i for i in self.user if i not in wanted]:
            state = engine.remove_goal(state, goal_id)
            del self.user[goal_id]
        for goal_id, (text, priority) in wanted.items():
            known = self.user.get(goal_id)
            try:
                if known is None and goal_id not in self.refused:
                    once, deadline = ends[goal_id]   # goals that end (docs/scenarios.md)
                    state = engine.add_goal(state, text, priority=priority, goal_id=goal_id,
                                            once=once, deadline=deadline)
                elif known is not None and known[1] != priority:
                    state = engine.set_priority(state, goal_id, priority)
                else:
                    continue
            except GoalError as exc:
                log.warning("goal %s %s refused by the engine: %s", goal_id, text, exc)
                self.refused.add(goal_id)
                continue
            self.user[goal_id] = (text, priority)
        return state


def validator(engines: dict[str, Any]):
    """validate(agent, goal, priority) -> "" or the engine's reason (goal_store.Validator),
    with ``engines``: agent -> Engine."""
    def validate(agent: str, goal: str, priority: int) -> str:
        engine = engines[agent]
        try:
            engine.add_goal(engine.initial_state(), goal, priority=priority, goal_id="check")
        except GoalError as exc:
            return str(exc)
        return ""

    return validate
