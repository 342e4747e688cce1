"""Scenario events injected into a running simulation (tests, fault drills). Never raises:
a bad event gives {"event": ..., "status": "failed", "reason": ...}.

Kinds:
- {"kind": "pedestrian", "ahead_of": AGENT, "dist": m, "lateral": m (+ = left, default 0),
   "speed": m/s (default 0), "heading": deg relative to the car (default 90, walking to its left),
   "id": optional}: a pedestrian steps out in front of a car.
- {"kind": "pedestrian", "x": m, "y": m, "heading": deg absolute, "speed": m/s, "id": optional}.
- {"kind": "block", "segment": SEG} / {"kind": "unblock", "segment": SEG}: close / reopen a road
  segment (traffic and package guidance avoid closed segments).
- {"kind": "package", "id": ID, "address": N, "street": NAME, "owner": AGENT}: a new package.
"""

from __future__ import annotations

import math
from typing import Any, Protocol

from world.driving.actors import Pedestrian
from world.driving.city import City
from world.driving.snapshot import PackageState
from world.errors import WorldError


class Simulation(Protocol):
    """The part of world.driving.simulation.Simulation that events change."""

    city: City
    cars: dict[str, Any]
    walkers: list[Pedestrian]
    packages: dict[str, PackageState]
    blocked: set[str]

    def add_pedestrian(self, p: Pedestrian) -> None: ...


def _num(event: dict, key: str, default: float | None = None) -> float:
    value = event.get(key, default)
    if value is None:
        raise WorldError(f"missing number {key!r}")
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise WorldError(f"{key}: expected a number, got {value!r}")
    return float(value)


def _pedestrian(sim: Simulation, event: dict) -> None:
    taken = {p.id for p in sim.walkers}
    fresh = next(f"M{k}" for k in range(len(taken) + 1, 2 * len(taken) + 2) if f"M{k}" not in taken)
    ident = event.get("id", fresh)
    if not isinstance(ident, str) or any(p.id == ident for p in sim.walkers):
        raise WorldError(f"pedestrian id {ident!r} is not a new string id")
    speed = _num(event, "speed", 0.0)
    if "ahead_of" in event:
        car = sim.cars.get(event["ahead_of"])
        if car is None:
            raise WorldError(f"ahead_of: unknown agent {event['ahead_of']!r}")
        dist, lateral = _num(event, "dist"), _num(event, "lateral", 0.0)
        h = car.body.angle
        x = car.body.position.x + dist * math.cos(h) - lateral * math.sin(h)
        y = car.body.position.y + dist * math.sin(h) + lateral * math.cos(h)
        heading = math.degrees(h) + _num(event, "heading", 90.0)
    else:
        x, y, heading = _num(event, "x"), _num(event, "y"), _num(event, "heading", 0.0)
    mode = "stand" if speed == 0.0 else "cross"
    sim.add_pedestrian(Pedestrian(ident, x, y, heading, speed=speed, mode=mode))


def _segment(sim: Simulation, event: dict) -> str:
    seg = event.get("segment")
    if not isinstance(seg, str):
        raise WorldError(f"segment: expected a segment id, got {seg!r}")
    return sim.city.segment(seg).id


def _package(sim: Simulation, event: dict) -> None:
    for key in ("id", "street", "owner"):
        if not isinstance(event.get(key), str):
            raise WorldError(f"{key}: expected a string, got {event.get(key)!r}")
    address = event.get("address")
    if isinstance(address, bool) or not isinstance(address, int):
        raise WorldError(f"address: expected an integer, got {address!r}")
    if event["id"] in sim.packages:
        raise WorldError(f"package {event['id']} exists already")
    sim.city.building(event["street"], address)   # raises for an unknown address
    sim.packages[event["id"]] = PackageState(event["id"], address, event["street"],
                                             event["owner"])


def apply_injection(sim: Simulation, event: Any) -> dict[str, Any]:
    """Apply one event to the simulation; return its outcome."""
    try:
        if not isinstance(event, dict):
            raise WorldError(f"expected a dict with a 'kind', got {event!r}")
        kind = event.get("kind")
        if kind == "pedestrian":
            _pedestrian(sim, event)
        elif kind == "block":
            sim.blocked.add(_segment(sim, event))
        elif kind == "unblock":
            sim.blocked.discard(_segment(sim, event))
        elif kind == "package":
            _package(sim, event)
        else:
            raise WorldError(f"unknown kind {kind!r}; known: pedestrian block unblock package")
    except WorldError as exc:
        return {"event": event, "status": "failed", "reason": f"inject: {exc}"}
    return {"event": event, "status": "done", "reason": ""}
