"""Scenario events injected into a running simulation (tests, fault drills). Never raises:
a bad event gives {"event": ..., "status": "failed", "reason": ...}.

Kinds:
- {"kind": "pedestrian", "ahead_of": AGENT, "dist": m, "lateral": m (+ = left, default 0),
   "speed": m/s (default 0), "heading": deg relative to the car (default 90, walking to its left),
   "id": optional}: a pedestrian steps out in front of a car.
- {"kind": "pedestrian", "x": m, "y": m, "heading": deg absolute, "speed": m/s, "id": optional}.
  Bounds: speed 0..10 m/s, dist and lateral within 500 m, x and y within 100 m of the grid.
- {"kind": "block", "segment": SEG} / {"kind": "unblock", "segment": SEG}: close / reopen a road
  segment (traffic and package guidance avoid closed segments).
- {"kind": "package", "id": ID, "address": N, "street": NAME, "owner": AGENT}: a new package;
  the owner must be an agent of the run. Ids are names a program can write: letters, digits,
  '_' and '-', a letter first, at most 32 characters.
"""

from __future__ import annotations

import math
import re
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


MAX_WALK_SPEED = 10.0    # [m/s] a pedestrian's speed (a sprinter runs 10)
MAX_AHEAD = 500.0        # [m] of `dist` and `lateral` from the car
MARGIN = 100.0           # [m] around the street grid where a pedestrian may be placed
MAX_HEADING = 3600.0     # [deg] either way
ID = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,31}")
"""An id the programs can name: a symbol of at most 32 characters (a letter first)."""


def _num(event: dict, key: str, lo: float, hi: float, default: float | None = None) -> float:
    """event[key] (or `default`): a finite number in [lo, hi]."""
    value = event.get(key, default)
    if value is None:
        raise WorldError(f"missing number {key!r}")
    if isinstance(value, bool) or not isinstance(value, int | float) or \
            not math.isfinite(value) or not lo <= value <= hi:
        raise WorldError(f"{key}: expected a number in [{lo:g}, {hi:g}], got {value!r}")
    return float(value)


def _ident(value: Any, what: str) -> str:
    if not isinstance(value, str) or not ID.fullmatch(value):
        raise WorldError(f"{what}: expected a name of letters, digits, '_' or '-' (a letter "
                         f"first, at most 32), got {value!r:.60}")
    return value


def _pedestrian(sim: Simulation, event: dict) -> None:
    taken = {p.id for p in sim.walkers}
    fresh = next(f"M{k}" for k in range(len(taken) + 1, 2 * len(taken) + 2) if f"M{k}" not in taken)
    ident = _ident(event.get("id", fresh), "id")
    if ident in taken:
        raise WorldError(f"pedestrian id {ident!r} is taken")
    speed = _num(event, "speed", 0.0, MAX_WALK_SPEED, 0.0)
    heading = _num(event, "heading", -MAX_HEADING, MAX_HEADING,
                   90.0 if "ahead_of" in event else 0.0)
    if "ahead_of" in event:
        car = sim.cars.get(event["ahead_of"])
        if car is None:
            raise WorldError(f"ahead_of: unknown agent {event['ahead_of']!r:.60}; agents: "
                             f"{sorted(sim.cars)}")
        dist = _num(event, "dist", -MAX_AHEAD, MAX_AHEAD)
        lateral = _num(event, "lateral", -MAX_AHEAD, MAX_AHEAD, 0.0)
        h = car.body.angle
        x = car.body.position.x + dist * math.cos(h) - lateral * math.sin(h)
        y = car.body.position.y + dist * math.sin(h) + lateral * math.cos(h)
        heading += math.degrees(h)
    else:
        w, h = sim.city.size
        x = _num(event, "x", -MARGIN, w + MARGIN)
        y = _num(event, "y", -MARGIN, h + MARGIN)
    mode = "stand" if speed == 0.0 else "cross"
    sim.add_pedestrian(Pedestrian(ident, x, y, heading, speed=speed, mode=mode))


def _segment(sim: Simulation, event: dict) -> str:
    seg = event.get("segment")
    if not isinstance(seg, str):
        raise WorldError(f"segment: expected a segment id, got {seg!r}")
    return sim.city.segment(seg).id


def _package(sim: Simulation, event: dict) -> None:
    _ident(event.get("id"), "id")
    if not isinstance(event.get("street"), str):
        raise WorldError(f"street: expected a street name, got {event.get('street')!r:.60}")
    if event.get("owner") not in sim.cars:
        raise WorldError(f"owner: expected one of the agents {sorted(sim.cars)}, got "
                         f"{event.get('owner')!r:.60}")
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
