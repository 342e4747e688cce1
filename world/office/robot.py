"""The robot: its state, its operations and its navigator (seed 003, section 6: `navigateToG`).

The navigator plans the shortest route over the floor graph with the door states and
obstacles it knows, and drives the body along it at the configured speed (local motion:
the body's velocity points at the next waypoint; pymunk moves it and reports contacts).
Every cycle it looks at the doors within sight: a door on its route that it sees closed or
blocked makes it replan, and fail when no route is left ("The module is able to compensate
for certain problems ... and will not report failure in these situations"). It fails on a
bump and on lack of progress. An armed false-success fault makes the next goto end "done"
in a room next to the goal, or halfway ("the navigate module may get confused and report a
success even in a failure situation").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import pairwise
from typing import Any, Protocol

import pymunk

from world.office.config import OfficeConfig
from world.office.floor import Floor, Point
from world.office.routes import (
    Obstacle,
    distances_from_node,
    distances_from_point,
    plan,
    truncate,
)
from world.office.snapshot import COUNTERS

ARRIVED = 0.05   # [m] from the last waypoint
PASSED = 0.15    # [m] from an intermediate waypoint
PROGRESS = 0.1   # [m] of route length that counts as progress
HALFWAY = "@halfway"   # the goal of a goto confused into stopping halfway


@dataclass
class Operation:
    """One command being carried out, or the last one (status running | done | failed)."""

    name: str
    args: tuple[Any, ...]
    action: list[Any]
    started: int
    status: str = "running"
    code: str = ""
    reason: str = ""
    ended: int = -1
    until: float = 0.0      # [s] when a timed operation completes
    goal: str = ""          # goto: the room driven to (another one under a false success)

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "args": list(self.args), "status": self.status,
                "code": self.code, "reason": self.reason, "started": self.started,
                "ended": self.ended}


@dataclass
class Robot:
    id: str
    body: pymunk.Body
    counters: dict[str, int] = field(default_factory=lambda: dict.fromkeys(COUNTERS, 0))
    carrying: list[str] = field(default_factory=list)
    op: Operation | None = None
    finished: list[dict[str, Any]] = field(default_factory=list)   # outcomes not yet reported
    route: list[tuple[str, Point]] = field(default_factory=list)   # (node, point) ahead
    travelled: float = 0.0
    heading: float = 0.0
    best_left: float = math.inf
    progress_at: float = 0.0
    known_doors: dict[str, tuple[str, int]] = field(default_factory=dict)
    known_people: dict[str, tuple[str, int]] = field(default_factory=dict)
    known_obstacles: dict[str, Obstacle] = field(default_factory=dict)
    observations: dict[str, tuple[str, int]] = field(default_factory=dict)
    confusion: str = ""       # armed false-success fault: "" | "wrong-room" | "halfway"
    stalled_until: float = 0.0

    @property
    def position(self) -> Point:
        return float(self.body.position.x), float(self.body.position.y)

    def running(self, name: str = "") -> bool:
        return self.op is not None and self.op.status == "running" and name in ("", self.op.name)

    def shut(self) -> frozenset[str]:
        """The doors the navigator believes it cannot pass."""
        return frozenset(d for d, (state, _) in self.known_doors.items() if state != "open")

    def halt(self) -> None:
        self.route = []
        self.body.velocity = (0.0, 0.0)


class Site(Protocol):
    """What the navigator reads of the simulation and how it reports."""

    floor: Floor
    config: OfficeConfig
    cycle: int
    time: float
    doors: dict[str, str]
    obstacles: dict[str, Any]

    def finish(self, robot: Robot, code: str = "", detail: str = "") -> None: ...
    def emit(self, kind: str, agent: str, **fields: Any) -> None: ...


def _left(robot: Robot) -> float:
    """Route length still ahead [m]."""
    if not robot.route:
        return 0.0
    pts = [robot.position] + [p for _, p in robot.route]
    return sum(math.dist(a, b) for a, b in pairwise(pts))


def _wrong_room(site: Site, robot: Robot, goal: str) -> str:
    """The room a confused navigator drives to instead of `goal`: the nearest other room it
    can reach, by path distance from the goal (the goal itself if there is none)."""
    shut, obstacles = robot.shut(), tuple(robot.known_obstacles.values())
    from_goal = distances_from_node(site.floor, goal, shut, obstacles)
    reachable = distances_from_point(site.floor, robot.position, shut, obstacles)
    others = sorted((from_goal[r.id], r.id) for r in site.floor.rooms
                    if r.id != goal and r.id in from_goal and r.id in reachable)
    return others[0][1] if others else goal


def _set_route(site: Site, robot: Robot) -> bool:
    """Plan the running goto's route from where the robot is; False when there is none."""
    op = robot.op
    halfway = op.goal == HALFWAY
    route = plan(site.floor, robot.position, op.args[0] if halfway else op.goal, robot.shut(),
                 tuple(robot.known_obstacles.values()))
    if route is None:
        return False
    if halfway:
        route = truncate(route, 0.5)
    nodes = route.nodes[len(route.nodes) - len(route.points):]
    robot.route = list(zip(nodes, route.points, strict=True))
    robot.best_left, robot.progress_at = _left(robot), site.time
    return True


def _no_route(site: Site, robot: Robot, goal: str) -> str:
    shut = sorted(robot.shut())
    known = ", ".join(f"{d} {robot.known_doors[d][0]}" for d in shut) or "no door shut"
    obstacles = ", ".join(sorted(robot.known_obstacles)) or "none"
    return f"no route from {site.floor.locate(*robot.position)} to {goal} (known: {known}; " \
           f"obstacles: {obstacles})"


def start_goto(site: Site, robot: Robot) -> None:
    """Plan the running goto operation's route, or end it (already there, no route)."""
    op = robot.op
    target = op.args[0]
    if site.floor.locate(*robot.position) == target:
        robot.halt()
        site.finish(robot)
        return
    op.goal = target
    if robot.confusion == "wrong-room":
        op.goal = _wrong_room(site, robot, target)
    elif robot.confusion == "halfway":
        op.goal = HALFWAY
    if not _set_route(site, robot):
        here = site.floor.locate(*robot.position)
        ends = [r.door for r in site.floor.rooms if r.id in (here, target)]
        shut = [d for d in ends if d in robot.shut()]
        code = f"door-{robot.known_doors[shut[0]][0]}" if shut else "no-route"
        site.finish(robot, code, _no_route(site, robot, target))


def drive(site: Site, robot: Robot, dt: float) -> None:
    """Set the body's velocity for one physics substep of dt [s]."""
    while robot.route and len(robot.route) > 1 and \
            math.dist(robot.position, robot.route[0][1]) < PASSED:
        robot.route.pop(0)
    if not robot.route or site.time < robot.stalled_until:
        robot.body.velocity = (0.0, 0.0)
        return
    (x, y), (tx, ty) = robot.position, robot.route[0][1]
    d = math.hypot(tx - x, ty - y)
    v = min(site.config.speed, d / dt)
    if d > 1e-9:
        robot.body.velocity = (v * (tx - x) / d, v * (ty - y) / d)
        robot.heading = math.degrees(math.atan2(ty - y, tx - x))
    else:
        robot.body.velocity = (0.0, 0.0)


def look(site: Site, robot: Robot) -> None:
    """Update the navigator's memory of what is within sight in the space it is in: the
    doors of that space, and known obstacles that are no longer there."""
    here = site.floor.locate(*robot.position)
    for door in site.floor.doors:
        if here in door.sides and math.dist(robot.position, (door.x, door.y)) <= \
                site.config.sight:
            state = site.doors[door.id]
            if robot.known_doors.get(door.id, ("open", 0))[0] != state:
                site.emit("door-seen", robot.id, door=door.id, state=state)
            robot.known_doors[door.id] = (state, site.cycle)
    for ident, (x, y, _) in sorted(robot.known_obstacles.items()):
        if ident not in site.obstacles and site.floor.locate(x, y) == here and \
                math.dist(robot.position, (x, y)) <= site.config.sight:
            del robot.known_obstacles[ident]
            site.emit("obstacle-gone", robot.id, obstacle=ident)


def check_goto(site: Site, robot: Robot) -> None:
    """After a step: arrival, a shut door ahead (replan or fail), lack of progress."""
    op = robot.op
    if robot.route and len(robot.route) == 1 and \
            math.dist(robot.position, robot.route[0][1]) < ARRIVED:
        robot.halt()
        if op.goal != op.args[0]:
            robot.counters["false_successes"] += 1
            site.emit("false-success", robot.id, target=op.args[0],
                      actual=site.floor.locate(*robot.position))
            robot.confusion = ""
        site.finish(robot)
        return
    shut = robot.shut()
    ahead = [n for n, _ in robot.route if n in shut]
    if ahead:
        door = ahead[0]
        if _set_route(site, robot):
            robot.counters["reroutes"] += 1
            site.emit("rerouted", robot.id, door=door, goal=op.args[0])
        else:
            state = robot.known_doors[door][0]
            robot.halt()
            site.finish(robot, f"door-{state}", f"{door} is {state}; "
                        + _no_route(site, robot, op.args[0]))
        return
    left = _left(robot)
    if left < robot.best_left - PROGRESS:
        robot.best_left, robot.progress_at = left, site.time
    elif site.time - robot.progress_at >= site.config.progress_time:
        robot.halt()
        site.finish(robot, "no-progress", f"less than {PROGRESS:g} m of progress in "
                    f"{site.time - robot.progress_at:g} s, {left:.1f} m from {op.args[0]}")
