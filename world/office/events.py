"""Scenario events and faults injected into a running office world (`teleo event`, scripted
[[events]], tests). Never raises: a bad event gives {"event", "status": "failed", "reason"}.

Kinds (every other key is the event's own):
- {"kind": "open" | "close" | "block", "door": DOOR}: open a door (and clear it), close it,
  or block it with a cart. Refused while a robot stands in the doorway.
- {"kind": "move", "person": P, "room": R}: the person walks to R, with what they hold.
- {"kind": "false-success", "agent": A, "mode": "wrong-room" | "halfway"}: A's next goto
  that has to drive reports done in a room next to the goal (default) or halfway.
- {"kind": "cool", "item": COFFEE, "temperature": C}: the coffee drops to C (default: room
  temperature).
- {"kind": "item", "item": ID, "type": KIND, "holder": P|R, "to": P|R, "temperature": C}:
  a new item (a request's mail, fax or coffee).
- {"kind": "give", "item": I, "to": P|R}: someone else hands the item to P or leaves it in R
  (not one a robot carries): a step of an errand the world made unnecessary.
- {"kind": "occupants", "room": R, "count": N}: N anonymous people in R (a meeting).
- {"kind": "obstacle", "x": m, "y": m, "radius": m, "id": ID}: something on the floor the
  robot's sensors miss (it bumps into it); {"kind": "clear", "obstacle": ID} removes it.
- {"kind": "stall", "agent": A, "seconds": s}: A's wheels slip: it cannot move for s seconds.
Every field is checked against EVENTS before use (type, range, no unknown field); at most
MAX_ITEMS items and MAX_OBSTACLES obstacles.
"""

from __future__ import annotations

import math
from typing import Any, Protocol

from bus.schema import FieldError, Int, Num, OneOf, Record, Str, Tagged, brief
from world.domain import event_outcome
from world.errors import WorldError
from world.office import EVENT_KINDS
from world.office.config import OfficeConfig
from world.office.floor import Floor
from world.office.operations import Item, Person
from world.office.physics import Physics
from world.office.snapshot import ObstacleState

CONFUSIONS = ("wrong-room", "halfway")
MAX_ITEMS = 500       # items on the floor at most (a new one beyond is refused)
MAX_OBSTACLES = 100   # obstacles at most

_DOOR = Record({"door": Str(what="a door id")})
_ROOM, _PLACE = Str(what="a room id"), Str(what="a person or room id")
_AGENT = Str(what="a robot's agent id")
_ID = Str(what="a new id", min_len=1)
EVENTS = Tagged({
    "open": _DOOR, "close": _DOOR, "block": _DOOR,
    "move": Record({"person": Str(what="a person"), "room": _ROOM}),
    "false-success": Record({"agent": _AGENT}, {"mode": OneOf(CONFUSIONS)}),
    "cool": Record({"item": Str(what="a coffee item")},
                   {"temperature": Num(-20.0, 100.0)}),
    "item": Record({"item": _ID, "type": Str(what="the item's kind (mail, fax, coffee, ...)",
                                             min_len=1),
                    "holder": _PLACE}, {"to": _PLACE, "temperature": Num(-20.0, 100.0)}),
    "give": Record({"item": Str(what="an item id"), "to": _PLACE}),
    "occupants": Record({"room": _ROOM, "count": Int(0, 1000)}),
    "obstacle": Record({"x": Num(), "y": Num()},
                       {"radius": Num(0.05, 2.0), "id": _ID}),
    "clear": Record({"obstacle": Str(what="an obstacle id")}),
    "stall": Record({"agent": _AGENT}, {"seconds": Num(0.0, 3600.0)}),
})
"""The office world's events and their fields (the module's docstring): checked before use."""


class Office(Protocol):
    """The part of world.office.simulation.OfficeSim that events change."""

    config: OfficeConfig
    floor: Floor
    physics: Physics
    time: float
    doors: dict[str, str]
    people: dict[str, Person]
    items: dict[str, Item]
    occupants: dict[str, int]
    obstacles: dict[str, ObstacleState]
    robots: dict[str, Any]

    def place_people(self) -> None: ...


def _num(event: dict, key: str, lo: float, hi: float, default: float | None = None) -> float:
    value = event.get(key, default)
    if value is None:
        raise WorldError(f"missing number {key!r}")
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) \
            or not lo <= value <= hi:
        raise WorldError(f"{key}: expected a number in [{lo:g}, {hi:g}], got {value!r}")
    return float(value)


def _name(event: dict, key: str, known: Any, what: str) -> str:
    value = event.get(key)
    if value not in known:
        raise WorldError(f"{key}: expected {what}, one of {sorted(known)}, got {value!r}")
    return value


def _door(sim: Office, event: dict) -> None:
    door = sim.floor.door(_name(event, "door", sim.doors, "a door id"))
    state = {"open": "open", "close": "closed", "block": "blocked"}[event["kind"]]
    if state != "open":
        inside = sim.physics.robots_near(door.x, door.y, door.width / 2 + 0.2)
        if inside:
            raise WorldError(f"door: robot {inside[0]} stands in the doorway of {door.id}")
    sim.doors[door.id] = state
    sim.physics.set_door(door, state)


def _move(sim: Office, event: dict) -> None:
    person = _name(event, "person", sim.people, "a person")
    room = _name(event, "room", {r.id for r in sim.floor.rooms}, "a room")
    sim.people[person].room, sim.people[person].away_until = room, -1.0
    sim.place_people()


def _new_item(sim: Office, event: dict) -> None:
    ident = event["item"]
    taken = set(sim.items) | set(sim.people) | set(sim.doors) | set(sim.robots) | \
        {r.id for r in sim.floor.rooms}
    if ident in taken:
        raise WorldError(f"item: expected a new id, got {ident!r}")
    if len(sim.items) >= MAX_ITEMS:
        raise WorldError(f"item: the floor has {len(sim.items)} items, the most it takes")
    kind = event["type"]
    places = set(sim.people) | {r.id for r in sim.floor.rooms}
    holder = _name(event, "holder", places, "a person or room")
    to = _name(event, "to", places, "a person or room") if "to" in event else ""
    cfg = sim.config
    temperature = _num(event, "temperature", cfg.coffee_ambient, 100.0, cfg.coffee_brew) \
        if kind == "coffee" else 0.0
    sim.items[ident] = Item(ident, kind, holder, to, temperature)


def _cool(sim: Office, event: dict) -> None:
    coffee = [i for i, item in sim.items.items() if item.kind == "coffee"]
    item = sim.items[_name(event, "item", coffee, "a coffee item")]
    item.temperature = _num(event, "temperature", -20.0, item.temperature,
                            sim.config.coffee_ambient)


def _obstacle(sim: Office, event: dict) -> None:
    x, y = _num(event, "x", 0.0, sim.floor.width), _num(event, "y", 0.0, sim.floor.height)
    radius = _num(event, "radius", 0.05, 2.0, 0.3)
    fresh = next(f"o{k}" for k in range(1, len(sim.obstacles) + 2) if f"o{k}" not in
                 sim.obstacles)
    ident = event.get("id", fresh)
    if ident in sim.obstacles:
        raise WorldError(f"id: expected a new obstacle id, got {ident!r}")
    if len(sim.obstacles) >= MAX_OBSTACLES:
        raise WorldError(f"id: the floor has {len(sim.obstacles)} obstacles, the most it takes")
    if sim.floor.locate(x, y) == "wall":
        raise WorldError(f"x, y: ({x:g}, {y:g}) is inside a wall, not in a room or corridor")
    near = sim.physics.robots_near(x, y, radius)
    if near:
        raise WorldError(f"x, y: ({x:g}, {y:g}) is under robot {near[0]}")
    sim.obstacles[ident] = ObstacleState(ident, x, y, radius)
    sim.physics.add_obstacle(ident, x, y, radius)


def _robot(sim: Office, event: dict) -> Any:
    return sim.robots[_name(event, "agent", sim.robots, "a robot's agent id")]


def _apply(sim: Office, event: dict) -> None:
    kind = event.get("kind")
    if kind in ("open", "close", "block"):
        _door(sim, event)
    elif kind == "move":
        _move(sim, event)
    elif kind == "false-success":
        _robot(sim, event).confusion = event.get("mode", "wrong-room")
    elif kind == "cool":
        _cool(sim, event)
    elif kind == "item":
        _new_item(sim, event)
    elif kind == "give":
        item = sim.items[_name(event, "item", sim.items, "an item id")]
        if item.holder in sim.robots:
            raise WorldError(f"item: {item.id} is carried by robot {item.holder}")
        places = set(sim.people) | {r.id for r in sim.floor.rooms}
        item.holder = _name(event, "to", places, "a person or room")
    elif kind == "occupants":
        room = _name(event, "room", {r.id for r in sim.floor.rooms}, "a room")
        sim.occupants[room] = event["count"]
    elif kind == "obstacle":
        _obstacle(sim, event)
    elif kind == "clear":
        ident = _name(event, "obstacle", sim.obstacles, "an obstacle id")
        del sim.obstacles[ident]
        sim.physics.remove_obstacle(ident)
    elif kind == "stall":
        _robot(sim, event).stalled_until = sim.time + _num(event, "seconds", 0.0, 3600.0)
    else:
        raise WorldError(f"unknown kind {kind!r}; known: {' '.join(EVENT_KINDS)}")


def apply_injection(sim: Office, event: Any) -> dict[str, Any]:
    """Apply one event to the world; return its outcome."""
    try:
        EVENTS.check(event)
    except FieldError as exc:
        return event_outcome(event, f"inject {brief(event.get('kind'))}: {exc}"
                             if isinstance(event, dict) else f"inject: {exc}")
    try:
        _apply(sim, event)
    except WorldError as exc:
        return event_outcome(event, f"inject {event['kind']!r}: {exc}")
    return event_outcome(event)
