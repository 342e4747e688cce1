"""Means-ends problem solving and skill learning on impasse (seed 000, "Problem Solving and
Skill Learning", Figure 3). Not built yet: ``SolverState`` is its part of EngineState."""

from .state import SolverState

__all__ = ["SolverState"]
