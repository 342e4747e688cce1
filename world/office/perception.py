"""Perception: a pure function from an office snapshot and one agent to that robot's percepts,
neutral lists `[type, id, attr, value, ...]` (docs/architecture.md). Every percept, attribute
and unit is documented in world/office/percepts.md.

What the robot perceives is what it knows: its own state and operation (always), the floor
plan with path distances computed over the doors and obstacles its navigator knows of, the
doors as last seen, people where last seen, every item with its holder (coffee temperature
only when carried or in sight), and the results of its observations.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

from world.base import r3
from world.office.config import OfficeConfig
from world.office.floor import build_floor
from world.office.routes import Obstacle, distances_from_node, distances_from_point
from world.office.snapshot import OfficeSnapshot, RobotState

Percept = list[Any]
ARGS = {"goto": ("target",), "observe": ("target",), "acquire": ("item", "from"),
        "deliver": ("item", "to")}



def _tf(flag: bool) -> str:
    return "T" if flag else "NIL"


def _shut(me: RobotState) -> frozenset[str]:
    return frozenset(d for d, (state, _) in me.known_doors.items() if state != "open")


def _obstacles(me: RobotState) -> tuple[Obstacle, ...]:
    return tuple((x, y, r) for _, (x, y, r) in sorted(me.known_obstacles.items()))


@lru_cache(maxsize=64)
def room_distances(config: OfficeConfig, shut: frozenset[str],
                   obstacles: tuple[Obstacle, ...]) -> tuple[tuple[str, str, float], ...]:
    """(a, b, path distance [m]) for every pair of rooms a < b that are connected."""
    floor = build_floor(config)
    out = []
    for a in floor.rooms:
        dist = distances_from_node(floor, a.id, shut, obstacles)
        out += [(a.id, b.id, dist[b.id]) for b in floor.rooms if a.id < b.id and b.id in dist]
    return tuple(sorted(out))


def _self(snap: OfficeSnapshot, me: RobotState) -> list[Percept]:
    out = [["robot", me.id, "room", me.place, "x", r3(me.x), "y", r3(me.y),
            "heading", r3(me.heading), "speed", r3(me.speed), "moving", _tf(me.speed > 0.01),
            "carrying", len(me.carrying), "capacity", snap.config.capacity,
            "travelled", r3(me.travelled)]]
    op = me.operation
    if op:
        names = ARGS.get(op["name"], ())
        named = [x for n, v in zip(names, op["args"], strict=False) for x in (n, v)]
        out.append(["operation", me.id, "action", op["name"], *named, "status", op["status"],
                    "reason", op["code"] or "NIL", "started", op["started"],
                    "ended", op["ended"]])
    return out


def _rooms(snap: OfficeSnapshot, me: RobotState) -> list[Percept]:
    floor = build_floor(snap.config)
    shut, obstacles = _shut(me), _obstacles(me)
    dist = distances_from_point(floor, (me.x, me.y), shut, obstacles)
    out = [["room", r.id, "kind", r.kind, "number", r.number, "door", r.door,
            "corridor", r.corridor, "dist", r3(dist.get(r.id, -1.0)),
            "reachable", _tf(r.id in dist), "x", r3(r.spot[0]), "y", r3(r.spot[1])]
           for r in floor.rooms]
    if snap.config.distances:
        out += [["distance", a, "to", b, "dist", r3(d)]
                for a, b, d in room_distances(snap.config, shut, obstacles)]
    for door in floor.doors:
        state, seen = me.known_doors.get(door.id, ["open", 0])
        where = ["room", door.sides[0]] if door.kind == "room" else ["corridor", door.sides[0]]
        visible = me.place in door.sides and \
            math.dist((me.x, me.y), (door.x, door.y)) <= snap.config.sight
        out.append(["door", door.id, "kind", door.kind, *where, "state", state, "seen", seen,
                    "visible", _tf(visible), "x", r3(door.x), "y", r3(door.y)])
    return out


def _people_and_items(snap: OfficeSnapshot, me: RobotState) -> list[Percept]:
    out = []
    for p in snap.people:
        room, seen = me.known_people.get(p.id, ["unknown", 0])
        out.append(["person", p.id, "room", room, "office", p.office,
                    "visible", _tf(p.room == me.place), "seen", seen])
    here = {p.id for p in snap.people if p.room == me.place} | {me.place, me.id}
    for i in snap.items:
        percept = ["item", i.id, "kind", i.kind, "holder", i.holder, "to", i.to or "NIL",
                   "visible", _tf(i.holder in here)]
        if i.kind == "coffee" and i.holder in here:
            percept += ["temp", r3(i.temperature),
                        "cold", _tf(i.temperature < snap.config.coffee_cold)]
        out.append(percept)
    out += [["observed", room, "result", result, "cycle", cycle]
            for room, (result, cycle) in me.observations.items()]
    out += [["obstacle", o, "x", r3(x), "y", r3(y), "radius", r3(r)]
            for o, (x, y, r) in me.known_obstacles.items()]
    out += [["other-robot", r.id, "room", r.place, "x", r3(r.x), "y", r3(r.y)]
            for r in snap.robots if r.id != me.id]
    return out


def perceive(snap: OfficeSnapshot, agent: str) -> list[Percept]:
    """The percepts of `agent`'s robot in `snap` (pure; raises WorldError for an unknown one)."""
    me = snap.robot(agent)
    return _self(snap, me) + _rooms(snap, me) + _people_and_items(snap, me)
