"""Valid world events of each domain, named from a running world (its agents, segments,
buildings, blocks, doors, people, rooms and items): the bases the fuzz drill mutates
(bench/faults/fuzz_bus.py, world-events-DOMAIN)."""

from __future__ import annotations

from typing import Any


def driving(world: Any, agent: str) -> list[dict]:
    segments = [s.id for s in world.city.segments[:6]]
    homes = world.city.buildings[:6]
    out: list[dict] = [
        {"kind": "pedestrian", "ahead_of": agent, "dist": 20.0, "lateral": 1.5, "speed": 1.4,
         "heading": 90.0},
        {"kind": "pedestrian", "ahead_of": agent, "dist": -35, "id": "W1"},
        {"kind": "pedestrian", "x": 150.0, "y": 40.0, "heading": 10.0, "speed": 0.8},
        {"kind": "pedestrian", "x": 10, "y": 300, "id": "W2"},
    ]
    out += [{"kind": k, "segment": s} for s in segments for k in ("block", "unblock")]
    out += [{"kind": "package", "id": f"P{9 + i}", "address": b.address, "street": b.street,
             "owner": agent} for i, b in enumerate(homes)]
    return out


def blocks(world: Any, agent: str) -> list[dict]:
    names = sorted(world.blocks)
    table = world.config.table.name
    out: list[dict] = [
        {"kind": "add", "block": "N1"}, {"kind": "add", "block": "N2", "on": table,
                                         "size": [1.0, 1.5], "column": 3},
        {"kind": "add", "block": "N3", "on": names[0], "size": [2, 2], "offset": 0.5},
        {"kind": "slip", "agent": agent},
    ]
    for name in names:
        out += [{"kind": "remove", "block": name}, {"kind": "knock", "block": name,
                                                      "speed": 2.5}]
    return out


def office(world: Any, agent: str) -> list[dict]:
    doors = sorted(world.doors)[:5]
    people = sorted(world.people)[:4]
    rooms = [r.id for r in world.floor.rooms][:5]
    items = sorted(world.items)[:3]
    coffee = [i for i, it in world.items.items() if it.kind == "coffee"]
    out: list[dict] = [{"kind": k, "door": d} for d in doors for k in ("open", "close", "block")]
    out += [{"kind": "move", "person": p, "room": r} for p, r in zip(people, rooms,
                                                                     strict=False)]
    out += [{"kind": "false-success", "agent": agent, "mode": "halfway"},
            {"kind": "false-success", "agent": agent},
            {"kind": "item", "item": "mail-new", "type": "mail", "holder": people[0],
             "to": rooms[1]},
            {"kind": "item", "item": "coffee-new", "type": "coffee", "holder": rooms[0],
             "temperature": 60.0},
            {"kind": "occupants", "room": rooms[2], "count": 3},
            {"kind": "obstacle", "x": 12.0, "y": 17.0, "radius": 0.3, "id": "box1"},
            {"kind": "obstacle", "x": 30.5, "y": 17.0},
            {"kind": "clear", "obstacle": "box1"},
            {"kind": "stall", "agent": agent, "seconds": 2.0}]
    out += [{"kind": "give", "item": i, "to": people[-1]} for i in items]
    out += [{"kind": "cool", "item": c, "temperature": 30.0} for c in coffee]
    return out


EVENT_BASES = {"driving": driving, "blocks": blocks, "office": office}
"""Domain -> bases(world, agent): a list of valid events of that world."""
