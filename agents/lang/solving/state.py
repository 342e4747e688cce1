"""The problem solver's part of EngineState: what it must keep between cycles and across a
restart of the executive process (goal stacks with their decisions)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True, slots=True)
class SolverState:
    """Empty until the problem solver exists."""

    def to_dict(self) -> dict[str, Any]:
        return {}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> SolverState:
        return cls()
