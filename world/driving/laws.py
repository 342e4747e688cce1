"""Detection of the events that matter to the driving laws, for one agent car after a step.
Pure functions of the city and the car; the simulation keeps the per-car memory (`LawState`).

Definitions (all on the car's centre point):
- off_road: the car enters a place that is neither a segment's road (|lateral| <= 6 m) nor an
  intersection box; counted once per excursion.
- yellow_crossings: on a segment, the car passes to the left of the yellow line relative to its
  direction of travel; counted once per excursion (inside intersections nothing is counted).
- speeding_cycles: cycles that end with speed > limit.
- deliveries: a carried package is delivered when the car has speed < 0.5 m/s within 10 m of the
  address's curb point and that point is on the car's right.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from world.driving.city import Building, City

DELIVERY_SPEED = 0.5    # [m/s]
DELIVERY_RADIUS = 10.0  # [m]


@dataclass
class LawState:
    off_road: bool = False
    wrong_side: bool = False
    speeding: bool = False


def road_events(city: City, state: LawState, x: float, y: float, heading: float,
                speed: float) -> list[str]:
    """Update a car's law memory after a step; return the kinds of the events that began."""
    events = []
    kind, seg_id, _, lat = city.locate(x, y)
    off = kind == "off"
    if off and not state.off_road:
        events.append("off_road")
    state.off_road = off
    if kind == "segment":
        seg = city.segment(seg_id)
        h = math.radians(heading)
        dot = math.cos(h) * seg.ux + math.sin(h) * seg.uy
        if abs(dot) >= math.cos(math.radians(45.0)):
            wrong = lat * (1 if dot > 0 else -1) > 0.0
            if wrong and not state.wrong_side:
                events.append("yellow_crossing")
            state.wrong_side = wrong
    speeding = speed > city.config.speed_limit
    if speeding and not state.speeding:
        events.append("speeding")
    state.speeding = speeding
    return events


def delivers(b: Building, x: float, y: float, heading: float, speed: float) -> bool:
    """True when a car at (x, y) [m], heading [deg], speed [m/s] has stopped at b's curb point
    with the point on its right."""
    if speed >= DELIVERY_SPEED:
        return False
    dx, dy = b.curb[0] - x, b.curb[1] - y
    if math.hypot(dx, dy) > DELIVERY_RADIUS:
        return False
    h = math.radians(heading)
    left = -dx * math.sin(h) + dy * math.cos(h)
    return left < 0.0
