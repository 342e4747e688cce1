"""Perception: a pure function from a world snapshot and one agent to that agent's percepts in
the seed's Table 3 form (seed 000), flattened to neutral lists `[type, id, attr, value, ...]`.

Agent-centred polar coordinates: `dist` [m] from the car's centre, `angle` [deg] relative to the
car's heading, in (-180, 180], positive = to the car's left. Only objects within the
configured perception range appear, except the car itself and the packages it carries (its
navigation system). Every attribute and unit is documented in world/driving/percepts.md.
"""

from __future__ import annotations

import math
from typing import Any

from world.angles import wrap
from world.base import r3
from world.driving.city import LINES, Building, City, Segment, build_city
from world.driving.navigation import aligned_segment, current_edge, edge_end, guide, target_edge
from world.driving.snapshot import CarState, WorldSnapshot

Percept = list[Any]



def polar(me: CarState, x: float, y: float) -> tuple[float, float]:
    """(dist [m], angle [deg], + = left of the heading) of a point seen from the car."""
    dx, dy = x - me.x, y - me.y
    return math.hypot(dx, dy), wrap(math.degrees(math.atan2(dy, dx)) - me.heading)


def axis_distance(seg: Segment, x: float, y: float) -> float:
    """Distance [m] from a point to a segment's axis (centre to centre)."""
    along, lat = seg.local(x, y)
    return math.hypot(max(0.0, -along, along - seg.length), lat)


def _self(city: City, snap: WorldSnapshot, me: CarState,
          aligned: tuple[Segment, int] | None) -> tuple[Percept, str]:
    kind, where, _, _ = city.locate(me.x, me.y)
    if kind == "segment":
        street = city.segment(where).street
    else:
        if kind == "off":
            where = min(city.segments, key=lambda s: (axis_distance(s, me.x, me.y), s.id)).id
            street = city.segment(where).street
        else:
            street = aligned[0].street if aligned else city.intersection(where).ew
    return ["self", me.id, "speed", r3(me.speed), "heading", r3(wrap(me.heading)),
            "wheel-angle", r3(me.wheel), "throttle", r3(me.throttle),
            "limit", r3(snap.config.speed_limit), "breakthrottle", r3(me.brake),
            "segment", where, "street", street, "x", r3(me.x), "y", r3(me.y)], street


def _lane_lines(me: CarState, seg: Segment) -> list[Percept]:
    h = math.radians(me.heading)
    left = (-math.sin(h), math.cos(h))
    normal = (-seg.uy, seg.ux)
    flip = 1.0 if normal[0] * left[0] + normal[1] * left[1] >= 0 else -1.0
    rel = wrap(seg.heading - me.heading)
    if rel > 90.0:
        rel -= 180.0
    elif rel <= -90.0:
        rel += 180.0
    _, car_lat = seg.local(me.x, me.y)
    out = []
    for name, color, offset in LINES:
        toward_left = (offset - car_lat) * flip
        out.append(["lane-line", f"{seg.id}-{name}", "color", color, "dist", r3(-toward_left),
                    "angle", r3(rel), "segment", seg.id])
    return out


def _buildings(city: City, me: CarState, reach: float) -> list[Percept]:
    out = []
    for b in city.buildings:
        cx, cy, radius = b.disc
        # every corner is at least (centre distance - radius) away: out of range, the
        # nearest corner is too (a margin keeps rounding from changing what is seen)
        if math.hypot(cx - me.x, cy - me.y) - radius > reach + 1e-6:
            continue
        corners = sorted((polar(me, x, y) for x, y in b.corners))
        (d1, a1), (d2, a2) = corners[0], corners[1]
        if d1 <= reach:
            out.append(["building", b.id, "address", b.address, "street", b.street,
                        "c1angle", r3(a1), "c1dist", r3(d1), "c2angle", r3(a2), "c2dist", r3(d2)])
    return out


def _packages(city: City, snap: WorldSnapshot, me: CarState) -> list[Percept]:
    out = []
    blocked = frozenset(snap.blocked)
    edge = current_edge(city, me.x, me.y, me.heading)
    for p in snap.packages:
        if p.owner != me.id:
            continue
        b = city.building(p.street, p.address)
        dist, angle = polar(me, *b.curb)
        turn, turn_dist = "NONE", 0.0
        if edge is not None:
            seg, d = edge
            g = guide(city, seg, d, seg.local(me.x, me.y)[0], b, blocked)
            turn, turn_dist = g.turn, g.dist
        out.append(["package", p.id, "address", p.address, "street", p.street,
                    "delivered", "T" if p.delivered else "NIL", "dist", r3(dist),
                    "angle", r3(angle), "next-turn", turn, "turn-dist", r3(turn_dist),
                    *_address_lane(city, b)])
    return out


def _address_lane(city: City, b: Building) -> list:
    """Where an address is served (for route planning in a program): the curb point, the
    segment, the heading [deg] of the lane that has the building on its right, and the
    intersection where that lane's block begins (with its position [m])."""
    seg_id, d = target_edge(b)
    seg = city.segment(seg_id)
    entry = city.intersection(edge_end(seg, -d))
    return ["x", r3(b.curb[0]), "y", r3(b.curb[1]), "segment", seg_id,
            "heading", r3(wrap(seg.heading if d > 0 else seg.heading + 180.0)),
            "entry", entry.id, "entry-x", r3(entry.x), "entry-y", r3(entry.y)]


def perceive(snap: WorldSnapshot, agent: str) -> list[Percept]:
    """The percepts of `agent` in `snap` (pure; raises WorldError for an unknown agent)."""
    city = build_city(snap.config)
    me = snap.car(agent)
    reach = snap.config.perception_range
    aligned = aligned_segment(city, me.x, me.y, me.heading)
    self_percept, my_street = _self(city, snap, me, aligned)
    segs = [(s, axis_distance(s, me.x, me.y)) for s in city.segments]
    segs = [(s, d) for s, d in segs if d <= reach]
    streets = sorted({s.street for s, _ in segs} | {my_street})
    out: list[Percept] = [["street", name] for name in streets]
    out.append(self_percept)
    blocked = set(snap.blocked)
    out += [["segment", s.id, "street", s.street, "dist", r3(d),
             "blocked", "T" if s.id in blocked else "NIL", "from", s.start, "to", s.end,
             "heading", r3(s.heading), "length", r3(s.length)] for s, d in segs]
    for n in city.intersections:
        dist, angle = polar(me, n.x, n.y)
        if dist <= reach:
            out.append(["intersection", n.id, "street", n.ew, "cross", n.ns, "dist", r3(dist),
                        "angle", r3(angle), "x", r3(n.x), "y", r3(n.y)])
    if aligned is not None:
        out += _lane_lines(me, aligned[0])
    out += _buildings(city, me, reach)
    for p in snap.pedestrians:
        dist, angle = polar(me, p.x, p.y)
        if dist <= reach:
            out.append(["man", p.id, "angle", r3(angle), "dist", r3(dist)])
    for c in snap.cars:
        if c.id != me.id:
            dist, angle = polar(me, c.x, c.y)
            if dist <= reach:
                out.append(["car", c.id, "angle", r3(angle), "dist", r3(dist),
                            "speed", r3(c.speed)])
    out += _packages(city, snap, me)
    return out
