"""The planner's part of EngineState: what it must keep between cycles and across a
restart of the executive process (tail-plans, head-plan, the projected state)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True, slots=True)
class PlannerState:
    """Empty until the planner exists."""

    def to_dict(self) -> dict[str, Any]:
        return {}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> PlannerState:
        return cls()
