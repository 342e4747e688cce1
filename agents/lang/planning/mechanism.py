"""ROGUE's planner as a mechanism (agents/lang/core/mechanism.py; seed 003): its program sections
(operators, requests, control-rules), the actions its operators can send, its impasse
handler by name "rogue", and its state, the "planner" slot of EngineState."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from ..core.mechanism import Mechanism
from .reader import PLANNING_SECTIONS
from .rogue import RoguePlanner
from .state import PlannerState


@dataclass(frozen=True)
class Planning(Mechanism):
    """The ROGUE planner: reads its sections, answers an impasse, keeps ``state.planner``."""

    name: str = "rogue"
    slot: str = "planner"
    state_type: type | None = PlannerState

    def sections(self) -> dict[str, Any]:
        return dict(PLANNING_SECTIONS)

    def program_actions(self, program: Any) -> Iterable:
        """Operators' :actions and :on-failure (seed 003)."""
        out: list = []
        for op in program.sections.get("operators", ()):
            out.extend((*op.skill.actions, *op.on_failure))
        return out

    def impasse_handlers(self) -> dict[str, Any]:
        return {"rogue": RoguePlanner}
