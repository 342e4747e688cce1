"""Static floor geometry built from an OfficeConfig: rooms, corridors, doors, walls and the floor
graph the robot's navigator plans on. Pure and cached per config.

Layout (y north, x east, [m]; D = room depth, C = corridor width, M = middle block depth):
    north rooms   y in [D+2C+M, 2D+2C+M]   doors on their south wall
    c-north       y in [D+C+M, D+2C+M]     full width
    middle block  y in [D+C, D+C+M]        solid; c-west and c-east run beside it
    c-south       y in [D, D+C]            full width
    south rooms   y in [0, D]              doors on their north wall
Rows run west to east from x = C. Graph nodes: each room's goal spot (the room id, 1.5 m
inside its door), each door's centre (the door id), the corridor point in front of each room
door (`<door>/front`) and the four corridor corners (`sw`, `se`, `nw`, `ne`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from itertools import pairwise

from world.errors import ConfigError, WorldError
from world.office.config import OfficeConfig, RoomSpec

Point = tuple[float, float]
Wall = tuple[Point, Point]


@dataclass(frozen=True)
class Room:
    id: str
    kind: str
    number: int
    x0: float
    y0: float
    x1: float
    y1: float
    door: str          # the id of its door
    corridor: str      # the corridor its door opens onto
    spot: Point        # where the robot stops inside
    inward: float      # +1: the room lies north of its door, -1: south

    def contains(self, x: float, y: float) -> bool:
        return self.x0 < x < self.x1 and self.y0 < y < self.y1

    def desk(self, k: int) -> Point:
        """The k-th person's place: along the back wall, away from the robot's spot."""
        depth = self.y1 - self.y0
        back = self.y1 - min(2.0, depth * 0.25) if self.inward > 0 else \
            self.y0 + min(2.0, depth * 0.25)
        offsets = (1.5, -1.5, 0.0, 2.5, -2.5, 0.8, -0.8, 2.0, -2.0)
        dx = offsets[k % len(offsets)] - 0.4 * (k // len(offsets))
        half = (self.x1 - self.x0) / 2 - 0.5
        return (self.x0 + self.x1) / 2 + max(-half, min(half, dx)), back


@dataclass(frozen=True)
class Door:
    """A room door (in a wall along x) or a fire door (across a corridor)."""

    id: str
    kind: str          # "room" | "fire"
    x: float
    y: float
    width: float
    across_x: bool     # True: the doorway is a gap along x in a wall of constant y
    sides: tuple[str, str]   # the spaces it joins (room, corridor) or (corridor, corridor)


@dataclass(frozen=True)
class Corridor:
    id: str
    x0: float
    y0: float
    x1: float
    y1: float

    def contains(self, x: float, y: float) -> bool:
        return self.x0 <= x <= self.x1 and self.y0 <= y <= self.y1


@dataclass(frozen=True)
class Floor:
    width: float
    height: float
    rooms: tuple[Room, ...]
    corridors: tuple[Corridor, ...]
    doors: tuple[Door, ...]
    walls: tuple[Wall, ...]
    blocks: tuple[tuple[float, float, float, float], ...]   # solid areas (x0, y0, x1, y1)
    nodes: dict[str, Point] = field(hash=False)
    edges: dict[str, tuple[tuple[str, float], ...]] = field(hash=False)
    lines: dict[str, tuple[str, ...]] = field(hash=False)   # corridor -> nodes along its axis

    def room(self, room_id: str) -> Room:
        for r in self.rooms:
            if r.id == room_id:
                return r
        raise WorldError(f"floor: no room {room_id!r}; rooms: {[r.id for r in self.rooms]}")

    def door(self, door_id: str) -> Door:
        for d in self.doors:
            if d.id == door_id:
                return d
        raise WorldError(f"floor: no door {door_id!r}; doors: {[d.id for d in self.doors]}")

    def has_room(self, room_id: str) -> bool:
        return any(r.id == room_id for r in self.rooms)

    def locate(self, x: float, y: float) -> str:
        """The room or corridor id at a point ("wall" inside solid parts)."""
        for r in self.rooms:
            if r.contains(x, y):
                return r.id
        for c in self.corridors:
            if c.contains(x, y):
                return c.id
        return "wall"

    def corridor_of(self, space: str) -> Corridor | None:
        return next((c for c in self.corridors if c.id == space), None)


def door_id(room_id: str) -> str:
    """A room's door: r-5309 -> d-5309."""
    return "d-" + room_id.removeprefix("r-")


def _row(specs: tuple[RoomSpec, ...], south: bool, cfg: OfficeConfig, y_wall: float,
         corridor: str) -> tuple[list[Room], list[Door], float]:
    rooms, doors, x = [], [], cfg.corridor_width
    depth, inward = cfg.room_depth, (-1.0 if south else 1.0)
    for s in specs:
        cx = x + s.width / 2
        y0, y1 = (y_wall - depth, y_wall) if south else (y_wall, y_wall + depth)
        d = door_id(s.id)
        spot = (cx, y_wall + inward * min(1.5, depth * 0.3))
        rooms.append(Room(s.id, s.kind, s.number, x, y0, x + s.width, y1, d, corridor, spot,
                          inward))
        doors.append(Door(d, "room", cx, y_wall, cfg.door_width, True, (s.id, corridor)))
        x += s.width
    return rooms, doors, x


def _room_walls(r: Room, door: Door, y_wall: float) -> list[Wall]:
    out: list[Wall] = [((r.x0, r.y0), (r.x0, r.y1)), ((r.x1, r.y0), (r.x1, r.y1))]
    far = r.y1 if r.inward > 0 else r.y0
    out.append(((r.x0, far), (r.x1, far)))
    half = door.width / 2
    out += [((r.x0, y_wall), (door.x - half, y_wall)), ((door.x + half, y_wall), (r.x1, y_wall))]
    return out


def _connect(edges: dict[str, list[tuple[str, float]]], nodes: dict[str, Point],
             a: str, b: str) -> None:
    length = math.dist(nodes[a], nodes[b])
    edges.setdefault(a, []).append((b, length))
    edges.setdefault(b, []).append((a, length))


@lru_cache(maxsize=32)
def build_floor(cfg: OfficeConfig) -> Floor:
    """The floor of a config (raises ConfigError for a layout that does not fit)."""
    C, D, M = cfg.corridor_width, cfg.room_depth, cfg.middle_depth
    inner = max(sum(r.width for r in cfg.south), sum(r.width for r in cfg.north))
    W, H = inner + 2 * C, 2 * D + 2 * C + M
    ys, yn = D + C / 2, D + 1.5 * C + M            # corridor axes
    south, s_doors, s_end = _row(cfg.south, True, cfg, D, "c-south")
    north, n_doors, n_end = _row(cfg.north, False, cfg, D + 2 * C + M, "c-north")
    corridors = (Corridor("c-south", 0.0, D, W, D + C), Corridor("c-north", 0.0, D + C + M, W,
                                                                 D + 2 * C + M),
                 Corridor("c-west", 0.0, D + C, C, D + C + M),
                 Corridor("c-east", W - C, D + C, W, D + C + M))
    nodes: dict[str, Point] = {"sw": (C / 2, ys), "se": (W - C / 2, ys), "nw": (C / 2, yn),
                               "ne": (W - C / 2, yn)}
    lines: dict[str, list[str]] = {"c-south": ["sw", "se"], "c-north": ["nw", "ne"],
                                   "c-west": ["sw", "nw"], "c-east": ["se", "ne"]}
    walls: list[Wall] = [((0, 0), (W, 0)), ((W, 0), (W, H)), ((W, H), (0, H)), ((0, H), (0, 0))]
    for r, d in zip(south + north, s_doors + n_doors, strict=True):
        nodes[r.id], nodes[d.id] = r.spot, (d.x, d.y)
        nodes[f"{d.id}/front"] = (d.x, ys if r.corridor == "c-south" else yn)
        lines[r.corridor].append(f"{d.id}/front")
        walls += _room_walls(r, d, d.y)
    fire = []
    for f in cfg.fire_doors:
        y0, y_axis = (D, ys) if f.corridor == "c-south" else (D + C + M, yn)
        if not C + 0.5 <= f.at <= W - C - 0.5:
            raise ConfigError(f"[world] fire door {f.id}: at {f.at:g} m is outside the corridor "
                              f"between its corners ({C + 0.5:g} .. {W - C - 0.5:g} m)")
        near = [n for n in lines[f.corridor] if abs(nodes[n][0] - f.at) < 0.8]
        if near:
            raise ConfigError(f"[world] fire door {f.id}: at {f.at:g} m is in front of a "
                              f"room door ({near[0].split('/')[0]}); move it 0.8 m or more away")
        fire.append(Door(f.id, "fire", f.at, y_axis, C, False, (f.corridor, f.corridor)))
        nodes[f.id] = (f.at, y_axis)
        lines[f.corridor].append(f.id)
    blocks = [(C, D + C, W - C, D + C + M)]
    if s_end < W - C - 1e-9:
        blocks.append((s_end, 0.0, W - C, D))
    if n_end < W - C - 1e-9:
        blocks.append((n_end, D + 2 * C + M, W - C, H))
    blocks += [(0.0, 0.0, C, D), (W - C, 0.0, W, D), (0.0, H - D, C, H), (W - C, H - D, W, H)]
    for x0, y0, x1, y1 in blocks:
        walls += [((x0, y0), (x1, y0)), ((x1, y0), (x1, y1)), ((x1, y1), (x0, y1)),
                  ((x0, y1), (x0, y0))]
    edges: dict[str, list[tuple[str, float]]] = {}
    for r, d in zip(south + north, s_doors + n_doors, strict=True):
        _connect(edges, nodes, r.id, d.id)
        _connect(edges, nodes, d.id, f"{d.id}/front")
    ordered: dict[str, tuple[str, ...]] = {}
    for name, members in lines.items():
        axis = 1 if name in ("c-west", "c-east") else 0
        ordered[name] = tuple(sorted(members, key=lambda n: (nodes[n][axis], n)))
        for a, b in pairwise(ordered[name]):
            _connect(edges, nodes, a, b)
    return Floor(W, H, tuple(south + north), corridors, tuple(s_doors + n_doors + fire),
                 tuple(walls), tuple(blocks), nodes,
                 {k: tuple(sorted(v)) for k, v in edges.items()}, ordered)
