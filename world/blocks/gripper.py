"""An agent's gripper (its hand): one block at most, one action per cycle, and the agent's
counters. It hovers HOVER [m] above the highest block, over the column of its last action."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from world.blocks.block import Block
from world.blocks.snapshot import COUNTERS

HOVER = 1.0     # [m] above the highest standing block (or above the held block's lower edge)


@dataclass
class Gripper:
    """`acted` is the action it performed (or tried) this cycle: a second one is refused."""

    agent: str
    hand: str
    x: float
    holding: Block | None = None
    acted: list[Any] | None = None
    counters: dict[str, int] = field(default_factory=lambda: dict.fromkeys(COUNTERS, 0))

    def count(self, name: str, n: int = 1) -> None:
        self.counters[name] += n

    def y(self, highest: float) -> float:
        """The gripper's height [m] given the top of the highest standing block."""
        held = self.holding.height if self.holding else 0.0
        return highest + HOVER + held
