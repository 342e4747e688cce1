"""The SCS interpreter's part of EngineState: what it must keep between cycles and across a
restart of the executive process (body threads, discount factors, the world model)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True, slots=True)
class ScsState:
    """Empty until the SCS interpreter exists."""

    def to_dict(self) -> dict[str, Any]:
        return {}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> ScsState:
        return cls()
