"""The means-ends problem solver and skill learner as a mechanism (agents/lang/core/mechanism.py;
seed 000, "Problem Solving and Skill Learning"): its impasse handler, by name "means-ends",
and its goal stacks, the "solver" slot of EngineState."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.mechanism import Mechanism
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
