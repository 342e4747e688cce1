"""A block: a dynamic pymunk box resting under gravity on the table or on other blocks.

A block held by a gripper leaves the physics (its body is taken out of the space) and comes back
where the gripper puts it, at rest; while in the space gravity, friction and contacts alone
decide whether it stays.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import pymunk

DENSITY = 1.0        # [kg/m^2]
FRICTION = 0.8
REST_SPEED = 0.05    # [m/s], [rad/s]: slower than this a block is at rest
UPRIGHT = 3.0        # [deg] from a multiple of 90 deg: a block this close lies flat


@dataclass(frozen=True)
class Box:
    """Where a block is: centre (x, y) [m] and angle [rad], with its size [m]."""

    x: float
    y: float
    angle: float
    width: float
    height: float

    @property
    def half(self) -> tuple[float, float]:
        """Half the horizontal and vertical extent [m] (of the rotated box)."""
        c, s = abs(math.cos(self.angle)), abs(math.sin(self.angle))
        return (self.width * c + self.height * s) / 2, (self.width * s + self.height * c) / 2

    @property
    def left(self) -> float:
        return self.x - self.half[0]

    @property
    def right(self) -> float:
        return self.x + self.half[0]

    @property
    def bottom(self) -> float:
        return self.y - self.half[1]

    @property
    def top(self) -> float:
        return self.y + self.half[1]

    def overlaps(self, other: Box, gap: float = 0.0) -> bool:
        """True when the two boxes' extents overlap by more than `gap` [m] both ways."""
        return (min(self.right, other.right) - max(self.left, other.left) > gap
                and min(self.top, other.top) - max(self.bottom, other.bottom) > gap)


def tilt(angle: float) -> float:
    """How far [deg] an angle [rad] is from lying flat on a face (0 .. 45)."""
    deg = math.degrees(angle) % 90.0
    return min(deg, 90.0 - deg)


@dataclass
class Block:
    """One block, its body and shape; `rest` is where it last came to rest (None while it
    moves), which is how a fall is told from a put."""

    name: str
    width: float
    height: float
    body: pymunk.Body = field(init=False)
    shape: pymunk.Poly = field(init=False)
    rest: Box | None = None    # where it last came to rest; None after a drop
    cause: str = ""            # the agent blamed if it falls before it rests again
    unsettled: bool = False    # it was moving at the end of the last step

    def __post_init__(self) -> None:
        self.body = pymunk.Body()
        self.shape = pymunk.Poly.create_box(self.body, (self.width, self.height))
        self.shape.density, self.shape.friction = DENSITY, FRICTION
        self.shape.elasticity = 0.0

    @property
    def box(self) -> Box:
        p = self.body.position
        return Box(float(p.x), float(p.y), float(self.body.angle), self.width, self.height)

    @property
    def moving(self) -> bool:
        return (self.body.velocity.length > REST_SPEED
                or abs(self.body.angular_velocity) > REST_SPEED)

    @property
    def upright(self) -> bool:
        return tilt(self.body.angle) <= UPRIGHT

    def place(self, x: float, bottom: float) -> None:
        """Put the block, flat and still, with its centre at x and its lower edge at bottom."""
        self.body.position = (x, bottom + self.height / 2)
        self.body.angle = 0.0
        self.body.velocity, self.body.angular_velocity = (0.0, 0.0), 0.0
        self.rest, self.cause, self.unsettled = self.box, "", False
