"""The means-ends problem solver and skill learner as a mechanism (agents/lang/core/mechanism.py;
seed 000, "Problem Solving and Skill Learning"): its impasse handler, by name "means-ends",
and its goal stacks, the "solver" slot of EngineState."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.mechanism import Mechanism
from .learned import clause_heads
from .solver import MeansEndsSolver
from .state import SolverState


@dataclass(frozen=True)
class Solving(Mechanism):
    """The means-ends solver: answers an impasse, keeps its goal stacks in ``state.solver``."""

    name: str = "means-ends"
    slot: str = "solver"
    state_type: type | None = SolverState

    def impasse_handlers(self) -> dict[str, Any]:
        return {"means-ends": MeansEndsSolver}

    summary_key: str = "learned"
    summary_rank: int = 1

    def summary(self, agent: Any) -> dict[str, Any] | None:
        """The agent's learned-skills file and the head of each skill in it (seed 000)."""
        if agent.learned is None:
            return None
        return {"file": agent.learned_file, "skills": clause_heads(agent.learned)}

    def summary_lines(self, name: str, entry: dict[str, Any]) -> list[str]:
        heads = entry["skills"]
        where = entry["file"] or "not saved: --learned-out FILE saves them"
        return [f"  {name}: learned skills {len(heads)} ({where})"
                + "".join(f"\n    {h}" for h in heads)]
