"""Perception: a pure function from a world snapshot and one agent to that agent's percepts in
the seed's Table 3 form (seed 000), flattened to neutral lists `[type, id, attr, value, ...]`.

Agent-centred polar coordinates: `dist` [m] from the car's centre, `angle` [deg] relative to the
car's heading, in (-180, 180], positive = to the car's left. Only objects within the
configured perception range appear, except the car itself and the packages it carries (its
navigation system). Every attribute and unit is documented in world/driving/percepts.md.

perceive       from a WorldSnapshot (tests, tools)
perceive_dict  from a snapshot dict as the bus delivers it (the perception process): checked
               against the snapshot schema, then read row by row as the dicts they are, with
               no object built per car, pedestrian or package; both give the same rows
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import lru_cache
from typing import Any

from world.angles import wrap
from world.base import r3, rebuild
from world.driving.city import LINES, Building, City, Segment, build_city
from world.driving.config import WorldConfig
from world.driving.navigation import (
    Guidance,
    aligned_segment,
    current_edge,
    edge_end,
    guide,
    target_edge,
)
from world.driving.snapshot import SNAPSHOT, CarState, WorldSnapshot, read_config
from world.errors import WorldError

Percept = list[Any]
Row = dict[str, Any]   # a car, pedestrian or package of a snapshot dict (SNAPSHOT's records)


def polar(me: CarState, x: float, y: float) -> tuple[float, float]:
    """(dist [m], angle [deg], + = left of the heading) of a point seen from the car."""
    dx, dy = x - me.x, y - me.y
    return math.hypot(dx, dy), wrap(math.degrees(math.atan2(dy, dx)) - me.heading)


def _bearing(me: CarState, x: float, y: float) -> float:
    """``polar``'s angle alone (worked out only for what is in range)."""
    return wrap(math.degrees(math.atan2(y - me.y, x - me.x)) - me.heading)


def axis_distance(seg: Segment, x: float, y: float) -> float:
    """Distance [m] from a point to a segment's axis (centre to centre)."""
    along, lat = seg.local(x, y)
    return math.hypot(max(0.0, -along, along - seg.length), lat)


def _axis_distances(city: City, x: float, y: float) -> list[float]:
    """``axis_distance`` of the point to every segment of the city, in its order."""
    out = []
    hypot = math.hypot
    for s in city.segments:
        dx, dy = x - s.x0, y - s.y0   # Segment.local, inline
        along, lat = dx * s.ux + dy * s.uy, -dx * s.uy + dy * s.ux
        out.append(hypot(max(0.0, -along, along - s.length), lat))
    return out


def _self(city: City, config: WorldConfig, me: CarState,
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
            "limit", r3(config.speed_limit), "breakthrottle", r3(me.brake),
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
    mx, my, hypot = me.x, me.y, math.hypot
    for b in _near(city, reach, math.floor(mx / _CELL), math.floor(my / _CELL)):
        cx, cy, radius = b.disc
        # every corner is at least (centre distance - radius) away: out of range, the
        # nearest corner is too (a margin keeps rounding from changing what is seen)
        if hypot(cx - mx, cy - my) - radius > reach + 1e-6:
            continue
        corners = b.corners
        dists = [hypot(x - mx, y - my) for x, y in corners]
        d1, d2, d3 = sorted(dists)[:3]
        if d1 > reach:
            continue
        if d1 == d2 or d2 == d3:   # a tie: the angles order them, as sorting polars does
            (d1, a1), (d2, a2) = sorted(polar(me, x, y) for x, y in corners)[:2]
        else:
            a1 = _bearing(me, *corners[dists.index(d1)])
            a2 = _bearing(me, *corners[dists.index(d2)])
        out.append(["building", b.id, "address", b.address, "street", b.street,   # r3 of
                    "c1angle", round(a1, 3) + 0.0, "c1dist", round(d1, 3) + 0.0,  # floats
                    "c2angle", round(a2, 3) + 0.0, "c2dist", round(d2, 3) + 0.0])
    return out


_CELL = 20.0   # [m] the side of the squares the buildings that may be in range are listed for


@lru_cache(maxsize=4096)
def _near(city: City, reach: float, i: int, j: int) -> tuple[Building, ...]:
    """The buildings (in the city's order) that the exact test of ``_buildings`` may let
    through from some point of the square [i, i + 1) x [j, j + 1) * _CELL: those whose disc
    comes within reach (and a metre) of the square."""
    x0, y0 = i * _CELL, j * _CELL
    out = []
    for b in city.buildings:
        cx, cy, radius = b.disc
        gap = math.hypot(max(x0 - cx, 0.0, cx - x0 - _CELL), max(y0 - cy, 0.0, cy - y0 - _CELL))
        if gap - radius <= reach + 1.0:
            out.append(b)
    return tuple(out)


def _guided(city: City, edge: tuple[Segment, int], b: Building, x: float, y: float,
            blocked: frozenset[str]) -> Guidance:
    """``guide`` for a car at (x, y) on ``edge``. Off the address's own edge the turn depends
    on the edge, the building and the blocked segments only: the route is searched once for
    them (``_turn``), and the distance to the turn is guide's own."""
    seg, d = edge
    along = seg.local(x, y)[0]
    if (seg.id, d) == target_edge(b):
        return guide(city, seg, d, along, b, blocked)
    travelled = along if d > 0 else seg.length - along
    return Guidance(_turn(city, seg.id, d, b.street, b.address, blocked),
                    round(seg.length - travelled, 3))


@lru_cache(maxsize=4096)
def _turn(city: City, seg_id: str, d: int, street: str, address: int,
          blocked: frozenset[str]) -> str:
    return guide(city, city.segment(seg_id), d, 0.0, city.building(street, address),
                 blocked).turn


def _packages(city: City, packages: Sequence[Row], blocked: frozenset[str], me: CarState
              ) -> list[Percept]:
    out = []
    edge = current_edge(city, me.x, me.y, me.heading)
    for p in packages:
        if p["owner"] != me.id:
            continue
        b = city.building(p["street"], p["address"])
        dist, angle = polar(me, *b.curb)
        turn, turn_dist = "NONE", 0.0
        if edge is not None:
            g = _guided(city, edge, b, me.x, me.y, blocked)
            turn, turn_dist = g.turn, g.dist
        out.append(["package", p["id"], "address", p["address"], "street", p["street"],
                    "delivered", "T" if p.get("delivered", False) else "NIL", "dist", r3(dist),
                    "angle", r3(angle), "next-turn", turn, "turn-dist", r3(turn_dist),
                    *_address_lane(city, p["street"], p["address"])])
    return out


@lru_cache(maxsize=1024)
def _address_lane(city: City, street: str, address: int) -> tuple:
    """Where an address is served (for route planning in a program): the curb point, the
    segment, the heading [deg] of the lane that has the building on its right, and the
    intersection where that lane's block begins (with its position [m]). Static: worked
    out once per city and address."""
    b = city.building(street, address)
    seg_id, d = target_edge(b)
    seg = city.segment(seg_id)
    entry = city.intersection(edge_end(seg, -d))
    return ("x", r3(b.curb[0]), "y", r3(b.curb[1]), "segment", seg_id,
            "heading", r3(wrap(seg.heading if d > 0 else seg.heading + 180.0)),
            "entry", entry.id, "entry-x", r3(entry.x), "entry-y", r3(entry.y))


def perceive(snap: WorldSnapshot, agent: str) -> list[Percept]:
    """The percepts of `agent` in `snap` (pure; raises WorldError for an unknown agent)."""
    me = snap.car(agent)
    return _seen(snap.config, me, [vars(c) for c in snap.cars],
                 [vars(p) for p in snap.pedestrians], [vars(p) for p in snap.packages],
                 snap.blocked)


def perceive_dict(d: dict[str, Any], agent: str) -> list[Percept]:
    """The percepts of `agent` in a snapshot dict (WorldSnapshot.to_dict's form, whole), as
    ``perceive`` gives them for WorldSnapshot.from_dict(d); raises WorldError naming what is
    wrong with the dict (as from_dict does) or the unknown agent."""
    config, me = rebuild(WorldSnapshot, SNAPSHOT, d,
                         lambda: (read_config(d["config"]), _car(d["cars"], agent)))
    if me is None:
        raise WorldError(f"snapshot of cycle {int(d['cycle'])}: no car {agent!r}; "
                         f"cars: {[c['id'] for c in d['cars']]}")
    return _seen(config, me, d["cars"], d["pedestrians"], d["packages"], d["blocked"])


def _car(cars: Sequence[Row], agent: str) -> CarState | None:
    for c in cars:
        if c["id"] == agent:
            return CarState(**c)
    return None


def _seen(config: WorldConfig, me: CarState, cars: Sequence[Row], pedestrians: Sequence[Row],
          packages: Sequence[Row], blocked_ids: Sequence[str]) -> list[Percept]:
    city = build_city(config)
    reach = config.perception_range
    aligned = aligned_segment(city, me.x, me.y, me.heading)
    self_percept, my_street = _self(city, config, me, aligned)
    segs = [(s, d) for s, d in zip(city.segments, _axis_distances(city, me.x, me.y),
                                    strict=True) if d <= reach]
    streets = sorted({s.street for s, _ in segs} | {my_street})
    out: list[Percept] = [["street", name] for name in streets]
    out.append(self_percept)
    blocked = frozenset(blocked_ids)
    out += [["segment", s.id, "street", s.street, "dist", r3(d),
             "blocked", "T" if s.id in blocked else "NIL", "from", s.start, "to", s.end,
             "heading", r3(s.heading), "length", r3(s.length)] for s, d in segs]
    for n in city.intersections:
        dist = math.hypot(n.x - me.x, n.y - me.y)
        if dist <= reach:
            out.append(["intersection", n.id, "street", n.ew, "cross", n.ns, "dist", r3(dist),
                        "angle", r3(_bearing(me, n.x, n.y)), "x", r3(n.x), "y", r3(n.y)])
    if aligned is not None:
        out += _lane_lines(me, aligned[0])
    out += _buildings(city, me, reach)
    out += _others(me, reach, pedestrians, cars)
    out += _packages(city, packages, blocked, me)
    return out


def _others(me: CarState, reach: float, pedestrians: Sequence[Row], cars: Sequence[Row]
            ) -> list[Percept]:
    """The pedestrians, then the other cars, in range."""
    out: list[Percept] = []
    mx, my, hypot = me.x, me.y, math.hypot
    for p in pedestrians:
        x, y = p["x"], p["y"]
        dist = hypot(x - mx, y - my)
        if dist <= reach:
            out.append(["man", p["id"], "angle", round(_bearing(me, x, y), 3) + 0.0,
                        "dist", round(dist, 3) + 0.0])
    for c in cars:
        if c["id"] != me.id:
            x, y = c["x"], c["y"]
            dist = hypot(x - mx, y - my)
            if dist <= reach:
                out.append(["car", c["id"], "angle", round(_bearing(me, x, y), 3) + 0.0,
                            "dist", round(dist, 3) + 0.0, "speed", r3(c["speed"])])
    return out
