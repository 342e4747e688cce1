"""ROGUE's planner and request handling (seed 003). Not built yet: ``PlannerState`` is its
part of EngineState."""

from .state import PlannerState

__all__ = ["PlannerState"]
