"""Shortest routes over the floor graph (the robot's navigator and the perceived distances).

A route starts at any point of a room or corridor: it joins the graph at the room's spot or
door, or at the two corridor nodes on either side of the point, and follows graph edges by
Dijkstra's algorithm (ties broken by node id, so routes are deterministic). Doors in `shut`
(closed or blocked, as far as the navigator knows) cannot be passed; an edge that runs within
`clearance` [m] of a known obstacle's rim cannot be used, except by a robot moving away
from an obstacle it touches.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Iterable
from dataclasses import dataclass
from itertools import pairwise

from world.office.floor import Floor, Point

START = "@start"
ROBOT_RADIUS = 0.25    # [m]
Obstacle = tuple[float, float, float]   # x, y, radius [m]


@dataclass(frozen=True)
class Route:
    """Nodes from START to the goal, their points [m] and the length [m] along them."""

    nodes: tuple[str, ...]
    points: tuple[Point, ...]
    length: float


def _closest(a: Point, b: Point, p: Point) -> tuple[float, float]:
    """(t in [0, 1], distance) of the point of segment ab nearest to p."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    n = dx * dx + dy * dy
    t = 0.0 if n == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / n))
    return t, math.dist((a[0] + t * dx, a[1] + t * dy), p)


def clear(a: Point, b: Point, obstacles: Iterable[Obstacle], leaving: bool = False) -> bool:
    """Whether a robot can drive from a to b without touching a known obstacle. leaving: a
    is the robot's own position, and moving away from an obstacle it touches is allowed."""
    for x, y, r in obstacles:
        t, d = _closest(a, b, (x, y))
        if d < r + ROBOT_RADIUS + 0.05 and not (leaving and t == 0.0):
            return False
    return True


def entries(floor: Floor, start: Point) -> list[str]:
    """The graph nodes a point joins the graph at (empty inside a wall)."""
    space = floor.locate(*start)
    if floor.has_room(space):
        room = floor.room(space)
        return [room.id, room.door]
    line = floor.lines.get(space)
    if not line:
        return []
    axis = 1 if space in ("c-west", "c-east") else 0
    coords = [floor.nodes[n][axis] for n in line]
    v = start[axis]
    if v <= coords[0]:
        return [line[0]]
    if v >= coords[-1]:
        return [line[-1]]
    k = next(i for i, c in enumerate(coords) if c >= v)
    return [line[k]] if coords[k] == v else [line[k - 1], line[k]]


def _search(floor: Floor, sources: list[tuple[str, float]], shut: frozenset[str],
            obstacles: tuple[Obstacle, ...]) -> tuple[dict[str, float], dict[str, str]]:
    dist: dict[str, float] = {}
    prev: dict[str, str] = {}
    heap = [(d, n, START) for n, d in sources]
    heapq.heapify(heap)
    while heap:
        d, node, before = heapq.heappop(heap)
        if node in dist:
            continue
        dist[node], prev[node] = d, before
        for nxt, length in floor.edges.get(node, ()):
            if nxt in dist or nxt in shut:
                continue
            if obstacles and not clear(floor.nodes[node], floor.nodes[nxt], obstacles):
                continue
            heapq.heappush(heap, (d + length, nxt, node))
    return dist, prev


def _sources(floor: Floor, start: Point, shut: frozenset[str],
             obstacles: tuple[Obstacle, ...]) -> list[tuple[str, float]]:
    return [(n, math.dist(start, floor.nodes[n])) for n in entries(floor, start)
            if n not in shut and clear(start, floor.nodes[n], obstacles, leaving=True)]


def plan(floor: Floor, start: Point, goal: str, shut: frozenset[str] = frozenset(),
         obstacles: tuple[Obstacle, ...] = ()) -> Route | None:
    """The shortest route from a point to a graph node (a room id: its spot), or None."""
    dist, prev = _search(floor, _sources(floor, start, shut, obstacles), shut, obstacles)
    if goal not in dist:
        return None
    nodes = [goal]
    while prev[nodes[-1]] != START:
        nodes.append(prev[nodes[-1]])
    nodes.reverse()
    points = [start] + [floor.nodes[n] for n in nodes]
    if math.dist(points[0], points[1]) < 1e-6:
        points.pop(0)
    else:
        nodes.insert(0, START)
    return Route(tuple(nodes), tuple(points), dist[goal])


def distances_from_point(floor: Floor, start: Point, shut: frozenset[str] = frozenset(),
                         obstacles: tuple[Obstacle, ...] = ()) -> dict[str, float]:
    """Path distance [m] from a point to every reachable node."""
    return _search(floor, _sources(floor, start, shut, obstacles), shut, obstacles)[0]


def distances_from_node(floor: Floor, node: str, shut: frozenset[str] = frozenset(),
                        obstacles: tuple[Obstacle, ...] = ()) -> dict[str, float]:
    """Path distance [m] from a graph node to every reachable node."""
    return _search(floor, [(node, 0.0)], shut, obstacles)[0]


def truncate(route: Route, fraction: float) -> Route:
    """The first `fraction` of a route's length (the navigator's "halfway" confusion)."""
    goal_len, run = route.length * fraction, 0.0
    points = [route.points[0]]
    for a, b in pairwise(route.points):
        seg = math.dist(a, b)
        if run + seg >= goal_len:
            t = (goal_len - run) / seg if seg else 0.0
            points.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
            break
        points.append(b)
        run += seg
    return Route(route.nodes[:len(points)], tuple(points), goal_len)
