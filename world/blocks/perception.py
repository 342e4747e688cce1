"""What an agent perceives of the Blocks World: the percept form of programs/blocks.tlp
(documented in percepts.md), a pure function of a snapshot dict.

    (table T xpos 0 ypos 0 height 2)     the table: column 0's x, the floor, its height
    (hand H1 status empty)               the agent's own gripper, or (hand H1 status C)
    (block A xpos 0 ypos 2 height 2)     a block: its centre's x, its lower edge, its height

Positions are rounded to the world's resolution [m] (a power of two, so the program's
`(= ?y1 (+ ?y2 ?h))` compares exact sums) and written as int when whole. A held block is
perceived off the table at xpos 99 ypos 99, whoever holds it.
"""

from __future__ import annotations

import math
from typing import Any

from world.blocks.block import Box
from world.blocks.snapshot import BlocksSnapshot, BlockState

HELD = 99     # [m] the xpos and ypos of a held block (programs/blocks.tlp)


def quantize(value: float, resolution: float) -> int | float:
    """`value` [m] to the nearest multiple of `resolution`; an int when whole.

    >>> quantize(1.9987, 0.25), quantize(3.13, 0.25), quantize(-0.01, 0.25)
    (2, 3.25, 0)
    """
    q = round(value / resolution) * resolution
    return int(q) if float(q).is_integer() else q


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """The agent's percepts: the table, its own hand, then every block by name. Raises
    WorldError for a malformed snapshot or an unknown agent."""
    snap = BlocksSnapshot.from_dict(snapshot)
    hand, res, table = snap.hand(agent), snap.resolution, snap.table
    out: list[list[Any]] = [
        ["table", table.name, "xpos", quantize(table.column_x(0), res), "ypos", 0,
         "height", quantize(table.height, res)],
        ["hand", hand.hand, "status", hand.holding or "empty"],
    ]
    out += [_block(b, res) for b in sorted(snap.blocks, key=lambda b: b.name)]
    return out


def _block(b: BlockState, res: float) -> list[Any]:
    if b.held_by:
        return ["block", b.name, "xpos", HELD, "ypos", HELD, "height", quantize(b.height, res)]
    box = Box(b.x, b.y, math.radians(b.angle), b.width, b.height)
    return ["block", b.name, "xpos", quantize(box.x, res), "ypos", quantize(box.bottom, res),
            "height", quantize(box.top - box.bottom, res)]
