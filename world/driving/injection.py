"""Scenario events injected into a running simulation (tests, fault drills). Never raises:
a bad event gives {"event": ..., "status": "failed", "reason": ...}.

Kinds:
- {"kind": "pedestrian", "ahead_of": AGENT, "dist": m, "lateral": m (+ = left, default 0),
   "speed": m/s (default 0), "heading": deg relative to the car (default 90, walking to its left),
   "id": optional}: a pedestrian steps out in front of a car.
- {"kind": "pedestrian", "x": m, "y": m, "heading": deg absolute, "speed": m/s, "id": optional}.
  Bounds: speed 0..10 m/s, dist and lateral within 500 m, x and y within 100 m of the grid;
  at most MAX_INJECTED pedestrians more than the city started with.
- {"kind": "block", "segment": SEG} / {"kind": "unblock", "segment": SEG}: close / reopen a road
  segment (traffic and package guidance avoid closed segments).
- {"kind": "package", "id": ID, "address": N, "street": NAME, "owner": AGENT}: a new package;
  the owner must be an agent of the run. Ids are names a program can write: letters, digits,
  '_' and '-', a letter first, at most 32 characters. At most MAX_INJECTED packages more than
  the scenario's.
Every field is checked against EVENTS before use: a field of the wrong type or out of range,
a missing one, or one the kind does not have (`unknown field 'colour'`) fails the event,
naming the field.
"""

from __future__ import annotations

import math
import re
from typing import Any, Protocol

from bus.schema import FieldError, Int, Num, Record, Str, Tagged, brief
from world.domain import event_outcome
from world.driving.actors import Pedestrian
from world.driving.city import City
from world.driving.config import WorldConfig
from world.driving.snapshot import PackageState
from world.errors import WorldError


class Simulation(Protocol):
    """The part of world.driving.simulation.Simulation that events change."""

    config: WorldConfig
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
MAX_ADDRESS = 10**6      # a building's number, either way
MAX_INJECTED = 200       # pedestrians and packages events may add, each (the city stays cheap)
ID = re.compile(r"[A-Za-z][A-Za-z0-9_-]{0,31}")
"""An id the programs can name: a symbol of at most 32 characters (a letter first)."""

_NAME = "a name of letters, digits, '_' or '-' (a letter first, at most 32)"
_ID = Str(what=_NAME, pattern=ID.pattern)
_AHEAD = Num(-MAX_AHEAD, MAX_AHEAD)
_AGENT = Str(what="an agent's name")
EVENTS = Tagged({
    "pedestrian": Record({}, {"ahead_of": _AGENT,
                              "dist": _AHEAD, "lateral": _AHEAD,
                              "speed": Num(0.0, MAX_WALK_SPEED),
                              "heading": Num(-MAX_HEADING, MAX_HEADING), "id": _ID,
                              "x": Num(), "y": Num()}),
    "block": Record({"segment": Str(what="a segment id", pattern=ID.pattern)}),
    "unblock": Record({"segment": Str(what="a segment id", pattern=ID.pattern)}),
    "package": Record({"id": _ID, "address": Int(-MAX_ADDRESS, MAX_ADDRESS),
                       "street": Str(what="a street name"), "owner": _AGENT}),
})
"""The driving world's events and their fields (the module's docstring): checked before use."""


def _pedestrian(sim: Simulation, event: dict) -> None:
    taken = {p.id for p in sim.walkers}
    if len(taken) >= sim.config.pedestrians + MAX_INJECTED:
        raise WorldError(f"pedestrian: the city has {len(taken)} pedestrians, the most it takes "
                         f"({MAX_INJECTED} more than its {sim.config.pedestrians})")
    fresh = next(f"M{k}" for k in range(len(taken) + 1, 2 * len(taken) + 2) if f"M{k}" not in taken)
    ident = event.get("id", fresh)
    if ident in taken:
        raise WorldError(f"id: pedestrian id {ident!r} is taken")
    speed = float(event.get("speed", 0.0))
    if "ahead_of" in event:
        other = sorted({"x", "y"} & set(event))
        if other:
            raise WorldError(f"{other[0]}: not with ahead_of (a pedestrian steps out ahead "
                             "of a car, or at x, y)")
        car = sim.cars.get(event["ahead_of"])
        if car is None:
            raise WorldError(f"ahead_of: unknown agent {event['ahead_of']!r}; agents: "
                             f"{sorted(sim.cars)}")
        if "dist" not in event:
            raise WorldError("dist: missing; expected a number in "
                             f"[{-MAX_AHEAD:g}, {MAX_AHEAD:g}] (ahead of the car [m])")
        dist, lateral = float(event["dist"]), float(event.get("lateral", 0.0))
        heading = float(event.get("heading", 90.0))
        h = car.body.angle
        x = car.body.position.x + dist * math.cos(h) - lateral * math.sin(h)
        y = car.body.position.y + dist * math.sin(h) + lateral * math.cos(h)
        heading += math.degrees(h)
    else:
        w, h = sim.city.size
        x, y = _within(event, "x", w), _within(event, "y", h)
        heading = float(event.get("heading", 0.0))
        other = sorted({"dist", "lateral"} & set(event))
        if other:
            raise WorldError(f"{other[0]}: only with ahead_of (a pedestrian steps out ahead "
                             "of a car, or at x, y)")
    mode = "stand" if speed == 0.0 else "cross"
    sim.add_pedestrian(Pedestrian(ident, x, y, heading, speed=speed, mode=mode))


def _within(event: dict, key: str, size: float) -> float:
    """event[key], a coordinate [m] within MARGIN of the street grid (0 .. size)."""
    value = event.get(key)
    if value is None or not -MARGIN <= value <= size + MARGIN:
        raise WorldError(f"{key}: expected a number in [{-MARGIN:g}, {size + MARGIN:g}], "
                         f"got {brief(value)}" if value is not None else
                         f"{key}: missing; expected a number in [{-MARGIN:g}, "
                         f"{size + MARGIN:g}] (or ahead_of and dist)")
    return float(value)


def _segment(sim: Simulation, event: dict) -> str:
    return sim.city.segment(event["segment"]).id


def _package(sim: Simulation, event: dict) -> None:
    if event["owner"] not in sim.cars:
        raise WorldError(f"owner: expected one of the agents {sorted(sim.cars)}, got "
                         f"{event['owner']!r}")
    if event["id"] in sim.packages:
        raise WorldError(f"id: package {event['id']} exists already")
    if len(sim.packages) >= len(sim.config.packages) + MAX_INJECTED:
        raise WorldError(f"package: the city has {len(sim.packages)} packages, the most it takes")
    sim.city.building(event["street"], event["address"])   # raises for an unknown address
    sim.packages[event["id"]] = PackageState(event["id"], event["address"], event["street"],
                                             event["owner"])


def apply_injection(sim: Simulation, event: Any) -> dict[str, Any]:
    """Apply one event to the simulation; return its outcome."""
    try:
        kind = EVENTS.check(event)["kind"]
        if kind == "pedestrian":
            _pedestrian(sim, event)
        elif kind == "block":
            sim.blocked.add(_segment(sim, event))
        elif kind == "unblock":
            sim.blocked.discard(_segment(sim, event))
        else:
            _package(sim, event)
    except (WorldError, FieldError) as exc:
        return event_outcome(event, f"inject: {exc}")
    return event_outcome(event)
