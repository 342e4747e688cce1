"""The table and the floor: static pymunk shapes. The table is a box from the floor (y = 0) to
its top (y = height) under every column; the floor reaches FLOOR_MARGIN beyond it each side,
between two walls, so a block knocked off the table lands on the floor and stays in sight."""

from __future__ import annotations

import pymunk

from world.blocks.block import FRICTION
from world.blocks.config import TableSpec

FLOOR_MARGIN = 8.0     # [m] of floor beyond each end of the table
WALL_HEIGHT = 60.0     # [m]


def build_table(space: pymunk.Space, spec: TableSpec) -> None:
    """Add the table, the floor and the two walls to the space's static body."""
    lo, hi = spec.span
    top = spec.height
    x0, x1 = floor_span(spec)
    shapes = [
        pymunk.Poly(space.static_body, [(lo, 0.0), (hi, 0.0), (hi, top), (lo, top)]),
        pymunk.Segment(space.static_body, (x0, 0.0), (x1, 0.0), 0.0),
        pymunk.Segment(space.static_body, (x0, 0.0), (x0, WALL_HEIGHT), 0.0),
        pymunk.Segment(space.static_body, (x1, 0.0), (x1, WALL_HEIGHT), 0.0),
    ]
    for s in shapes:
        s.friction, s.elasticity = FRICTION, 0.0
    space.add(*shapes)


def floor_span(spec: TableSpec) -> tuple[float, float]:
    """The floor's ends [m] (the walls stand there)."""
    lo, hi = spec.span
    return lo - FLOOR_MARGIN, hi + FLOOR_MARGIN
