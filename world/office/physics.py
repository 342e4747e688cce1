"""The pymunk space of the office floor: walls, door leaves and carts, people, obstacles and
the robots' bodies. Every contact a robot's body starts with anything is recorded with a
label naming what it touched ("wall", "door d-5309", "obstacle o1", "person jhm",
"robot R2"); the simulation turns those into bumps.
"""

from __future__ import annotations

import math
from typing import Any

import pymunk

from world.office.floor import Door, Floor, Point
from world.office.routes import ROBOT_RADIUS

WALL_RADIUS = 0.05     # [m] half the thickness of a wall segment
PERSON_RADIUS = 0.3    # [m]
CART = 0.6             # [m] side of the cart that blocks a door
ROBOT_TYPE = 1


class Physics:
    """One floor's bodies and shapes, and the robot contacts of the last step."""

    def __init__(self, floor: Floor) -> None:
        self.space = pymunk.Space()
        self.labels: dict[pymunk.Shape, str] = {}
        self.contacts: list[tuple[str, str]] = []
        self.robots: dict[str, pymunk.Body] = {}
        self.people: dict[str, pymunk.Body] = {}
        self._doors: dict[str, list[pymunk.Shape]] = {}
        self._obstacles: dict[str, pymunk.Shape] = {}
        self.space.on_collision(begin=self._begin)
        for a, b in floor.walls:
            self._static(pymunk.Segment(self.space.static_body, a, b, WALL_RADIUS), "wall")

    def _static(self, shape: pymunk.Shape, label: str) -> pymunk.Shape:
        shape.friction, shape.elasticity = 0.0, 0.0
        self.space.add(shape)
        self.labels[shape] = label
        return shape

    def _begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        a, b = arbiter.shapes
        for mine, other in ((a, b), (b, a)):
            if mine.collision_type == ROBOT_TYPE:
                self.contacts.append((self.labels[mine].split()[1], self.labels[other]))

    def set_door(self, door: Door, state: str) -> None:
        """Put the door's leaf (closed), a cart (blocked) or nothing (open) in its doorway."""
        for shape in self._doors.pop(door.id, []):
            self.space.remove(shape)
            del self.labels[shape]
        body, label, half = self.space.static_body, f"door {door.id}", door.width / 2
        if state == "closed":
            a, b = ((door.x - half, door.y), (door.x + half, door.y)) if door.across_x else \
                ((door.x, door.y - half), (door.x, door.y + half))
            self._doors[door.id] = [self._static(pymunk.Segment(body, a, b, WALL_RADIUS), label)]
        elif state == "blocked":
            c, h = (door.x, door.y), CART / 2
            box = [(c[0] - h, c[1] - h), (c[0] + h, c[1] - h), (c[0] + h, c[1] + h),
                   (c[0] - h, c[1] + h)]
            self._doors[door.id] = [self._static(pymunk.Poly(body, box), label)]

    def add_robot(self, agent: str, at: Point) -> pymunk.Body:
        body = pymunk.Body(40.0, float("inf"))
        body.position = at
        shape = pymunk.Circle(body, ROBOT_RADIUS)
        shape.friction, shape.elasticity, shape.collision_type = 0.0, 0.0, ROBOT_TYPE
        self.space.add(body, shape)
        self.labels[shape] = f"robot {agent}"
        self.robots[agent] = body
        return body

    def place_person(self, person: str, at: Point) -> None:
        body = self.people.get(person)
        if body is None:
            body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
            shape = pymunk.Circle(body, PERSON_RADIUS)
            self.space.add(body, shape)
            self.labels[shape] = f"person {person}"
            self.people[person] = body
        body.position = at
        self.space.reindex_shapes_for_body(body)

    def add_obstacle(self, ident: str, x: float, y: float, radius: float) -> None:
        shape = pymunk.Circle(self.space.static_body, radius, (x, y))
        self._obstacles[ident] = self._static(shape, f"obstacle {ident}")

    def remove_obstacle(self, ident: str) -> None:
        shape = self._obstacles.pop(ident)
        self.space.remove(shape)
        del self.labels[shape]

    def robots_near(self, x: float, y: float, reach: float) -> list[str]:
        """Robots whose body comes within `reach` [m] of a point (a doorway about to shut)."""
        return sorted(a for a, b in self.robots.items()
                      if math.dist(b.position, (x, y)) < reach + ROBOT_RADIUS)

    def step(self, dt: float) -> None:
        self.space.step(dt)
