"""The problem solver's part of a Decision (explanation.Section): the goal stacks as they
stand after the cycle, what the solver did this cycle and the skills it learned."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .state import GoalStack, StackEntry


@dataclass(frozen=True, slots=True)
class SolverSection:
    """``stacks``: every goal stack after this cycle; ``events``: decisions, executions,
    pops, backtracks and failures of this cycle, in order; ``solving``: the goals problem
    solving ran for (an impasse this cycle); ``learned``: skill clauses learned this cycle."""

    stacks: tuple[GoalStack, ...] = ()
    events: tuple[str, ...] = ()
    solving: tuple[str, ...] = ()
    learned: tuple[str, ...] = ()
    name: str = "solver"

    def stack(self, goal_id: str) -> list[str]:
        """The (sub)goals on the stack of ``goal_id`` after this cycle, bottom first."""
        return next((s.goals() for s in self.stacks if s.goal_id == goal_id), [])

    def to_dict(self) -> dict[str, Any]:
        return {"stacks": [{"goal_id": s.goal_id, "started": s.started,
                            "entries": [_entry(e) for e in s.entries]} for s in self.stacks],
                "events": list(self.events), "solving": list(self.solving),
                "learned": list(self.learned)}

    def lines(self) -> list[str]:
        out = []
        for s in self.stacks:
            out.append(f"goal stack of {s.goal_id} (problem solving since cycle {s.started}):")
            for depth, e in enumerate(s.entries):
                out.append(f"  {depth + 1} {e.goal}  <- {e.why}")
        if self.events:
            out.append("problem solving:")
            out += [f"  {ev}" for ev in self.events]
        if self.learned:
            out.append("learned:")
            for text in self.learned:
                out += [f"  {line}" for line in text.splitlines()]
        return out


def _entry(e: StackEntry) -> dict[str, Any]:
    way = e.decision
    return {"goal": e.goal, "why": e.why,
            "decision": None if way is None else
            {"kind": way.kind, "name": way.name, "shows": way.shows,
             "bindings": dict(way.bindings), "conditions": list(way.conditions),
             "alternative": e.chosen + 1, "of": len(e.alternatives)},
            "failures": list(e.failures)}
