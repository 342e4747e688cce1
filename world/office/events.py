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
"""

from __future__ import annotations

import math
from typing import Any, Protocol

from world.errors import WorldError
from world.office import EVENT_KINDS
from world.office.config import OfficeConfig
from world.office.floor import Floor
from world.office.operations import Item, Person
from world.office.physics import Physics
from world.office.snapshot import ObstacleState

CONFUSIONS = ("wrong-room", "halfway")


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
    if not isinstance(value, str) or value not in known:
        raise WorldError(f"{key}: expected {what}, one of {sorted(known)}, got {value!r}")
    return value


def _door(sim: Office, event: dict) -> None:
    door = sim.floor.door(_name(event, "door", sim.doors, "a door id"))
    state = {"open": "open", "close": "closed", "block": "blocked"}[event["kind"]]
    if state != "open":
        inside = sim.physics.robots_near(door.x, door.y, door.width / 2 + 0.2)
        if inside:
            raise WorldError(f"robot {inside[0]} stands in the doorway of {door.id}")
    sim.doors[door.id] = state
    sim.physics.set_door(door, state)


def _move(sim: Office, event: dict) -> None:
    person = _name(event, "person", sim.people, "a person")
    room = _name(event, "room", {r.id for r in sim.floor.rooms}, "a room")
    sim.people[person].room, sim.people[person].away_until = room, -1.0
    sim.place_people()


def _new_item(sim: Office, event: dict) -> None:
    ident = event.get("item")
    taken = set(sim.items) | set(sim.people) | set(sim.doors) | set(sim.robots) | \
        {r.id for r in sim.floor.rooms}
    if not isinstance(ident, str) or not ident or ident in taken:
        raise WorldError(f"item: expected a new id, got {ident!r}")
    kind = event.get("type")
    if not isinstance(kind, str) or not kind:
        raise WorldError(f"type: expected the item's kind (mail, fax, coffee, ...), got {kind!r}")
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
    if not isinstance(ident, str) or not ident or ident in sim.obstacles:
        raise WorldError(f"id: expected a new obstacle id, got {ident!r}")
    if sim.floor.locate(x, y) == "wall":
        raise WorldError(f"({x:g}, {y:g}) is inside a wall, not in a room or corridor")
    near = sim.physics.robots_near(x, y, radius)
    if near:
        raise WorldError(f"({x:g}, {y:g}) is under robot {near[0]}")
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
        mode = event.get("mode", "wrong-room")
        if mode not in CONFUSIONS:
            raise WorldError(f"mode: expected one of {list(CONFUSIONS)}, got {mode!r}")
        _robot(sim, event).confusion = mode
    elif kind == "cool":
        _cool(sim, event)
    elif kind == "item":
        _new_item(sim, event)
    elif kind == "give":
        item = sim.items[_name(event, "item", sim.items, "an item id")]
        if item.holder in sim.robots:
            raise WorldError(f"item {item.id} is carried by robot {item.holder}")
        places = set(sim.people) | {r.id for r in sim.floor.rooms}
        item.holder = _name(event, "to", places, "a person or room")
    elif kind == "occupants":
        room = _name(event, "room", {r.id for r in sim.floor.rooms}, "a room")
        count = event.get("count")
        if isinstance(count, bool) or not isinstance(count, int) or not 0 <= count <= 1000:
            raise WorldError(f"count: expected an integer in [0, 1000], got {count!r}")
        sim.occupants[room] = count
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
        if not isinstance(event, dict):
            raise WorldError(f"expected a dict with a 'kind', got {event!r:.80}")
        _apply(sim, event)
    except WorldError as exc:
        return {"event": event, "status": "failed", "reason": f"inject {event.get('kind')!r}: "
                f"{exc}" if isinstance(event, dict) else f"inject: {exc}"}
    return {"event": event, "status": "done", "reason": ""}
