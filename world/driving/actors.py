"""Simulator-driven actors: pedestrians and traffic vehicles. Their behaviour rules:

Pedestrians walk the sidewalk of a street (WALK_OFFSET [m] from its axis) at 1.4 m/s, turning back
at the street's ends. Mid-block, a walking pedestrian starts to cross the road with probability
`crossing_rate * dt` per step (seeded), walks straight across to the other sidewalk, and walks on.
A pedestrian hit by a car falls ("down") and stays. Injected pedestrians stand or walk straight.

Traffic vehicles follow the right lane of their street at the speed limit (slowing to 6 m/s for
turns),
choosing a random legal exit at each intersection (never a U-turn, never a blocked segment).
They stop for any pedestrian, or vehicle going their way, in a corridor ahead (2 m either side,
as far as their braking distance plus 8 m). At intersections they yield: approaching the box a
vehicle claims it only if no vehicle is inside, no other traffic vehicle has claimed it, and the
lane after its turn has room (don't block the box); otherwise it stops at the box edge. A claim
holds until the vehicle is through (it will not stop for the box once committed).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

import numpy as np

from world.angles import wrap
from world.driving.city import ROAD_HALF, WALK_OFFSET, City
from world.driving.navigation import exits
from world.driving.paths import Key, Polyline, node_of

Vehicle = tuple[str, float, float, float]   # id, x [m], y [m], heading [deg]
WALK_SPEED = 1.4          # [m/s]
TURN_SPEED = 6.0          # [m/s] traffic speed through turns
TRAFFIC_ACCEL, TRAFFIC_BRAKE = 2.0, 6.0   # [m/s^2]


@dataclass
class Pedestrian:
    id: str
    x: float
    y: float
    heading: float            # [deg]
    speed: float = WALK_SPEED
    mode: str = "walk"        # walk | cross | stand | down
    street: str | None = None
    side: int = 1             # which sidewalk: +1 left of the street axis, -1 right
    s: float = 0.0            # [m] along the street from its first intersection
    lat: float = 0.0          # [m] from the street axis, + = left
    direction: int = 1        # +1 along the axis, -1 against


def street_axis(city: City, name: str) -> tuple[float, float, float, float, float]:
    """(x0, y0, ux, uy, length) of a whole street [m]."""
    cfg, L = city.config, city.config.block_length
    if name in cfg.ns_streets:
        return cfg.ns_streets.index(name) * L, 0.0, 0.0, 1.0, (len(cfg.ew_streets) - 1) * L
    return 0.0, cfg.ew_streets.index(name) * L, 1.0, 0.0, (len(cfg.ns_streets) - 1) * L


def spawn_pedestrian(city: City, rng: random.Random, ident: str) -> Pedestrian:
    streets = city.config.ns_streets + city.config.ew_streets
    p = Pedestrian(ident, 0.0, 0.0, 0.0, street=streets[rng.randrange(len(streets))])
    p.side = rng.choice((1, -1))
    p.direction = rng.choice((1, -1))
    p.s = rng.uniform(0.0, street_axis(city, p.street)[4])
    p.lat = p.side * WALK_OFFSET
    _place(city, p)
    return p


def _place(city: City, p: Pedestrian) -> None:
    x0, y0, ux, uy, _ = street_axis(city, p.street)
    p.x, p.y = x0 + p.s * ux - p.lat * uy, y0 + p.s * uy + p.lat * ux
    base = math.degrees(math.atan2(uy, ux))
    if p.mode == "cross":
        p.heading = wrap(base - 90.0 * p.side)
    else:
        p.heading = wrap(base if p.direction > 0 else base + 180.0)


def step_pedestrian(city: City, p: Pedestrian, rng: random.Random, dt: float) -> None:
    """Advance one pedestrian by dt [s]; draws from rng only while walking a street."""
    if p.mode == "down":
        return
    if p.street is None:                       # injected: stands, or walks straight on
        h = math.radians(p.heading)
        p.x += p.speed * math.cos(h) * dt
        p.y += p.speed * math.sin(h) * dt
        return
    length = street_axis(city, p.street)[4]
    L = city.config.block_length
    if p.mode == "walk":
        p.s += p.direction * p.speed * dt
        if not 0.0 <= p.s <= length:
            p.s = min(max(p.s, 0.0), length)
            p.direction = -p.direction
        mid_block = 15.0 < p.s % L < L - 15.0
        if mid_block and rng.random() < city.config.crossing_rate * dt:
            p.mode = "cross"
    elif p.mode == "cross":
        target = -p.side * WALK_OFFSET
        move = p.speed * dt
        if abs(target - p.lat) <= move:
            p.lat, p.side, p.mode = target, -p.side, "walk"
            p.direction = rng.choice((1, -1))
        else:
            p.lat += math.copysign(move, target - p.lat)
    _place(city, p)


@dataclass
class Traffic:
    id: str
    key: Key                  # the lane or turn piece it is on
    s: float                  # [m] along that piece
    speed: float              # [m/s]
    x: float = 0.0
    y: float = 0.0
    heading: float = 0.0
    exit: Key | None = None   # on a lane piece: the turn it will take at its end
    committed: bool = False   # has claimed the intersection ahead (will not stop for it)


def place_traffic(t: Traffic, paths: dict[Key, Polyline]) -> None:
    t.x, t.y, t.heading = paths[t.key].pose(t.s)


def corridors_blocked(traffic: list[Traffic], vehicles: list[Vehicle],
                      walkers: list[tuple[float, float]]) -> list[bool]:
    """For each traffic vehicle: is a pedestrian, or a vehicle going its way (headings within
    45 deg), in the corridor ahead (2 m either side, 0.5 m to braking distance + 8 m)? Cross
    traffic is left to the intersection rule: waiting cross traffic must not stall a turning car.
    Vectorised over all pairs (numpy) from the positions at the start of the step."""
    if not traffic:
        return []
    tx = np.array([t.x for t in traffic])
    ty = np.array([t.y for t in traffic])
    th = np.radians([t.heading for t in traffic])
    reach = np.array([t.speed for t in traffic]) ** 2 / (2 * TRAFFIC_BRAKE) + 8.0
    ox = np.array([v[1] for v in vehicles] + [w[0] for w in walkers])
    oy = np.array([v[2] for v in vehicles] + [w[1] for w in walkers])
    oh = np.radians([v[3] for v in vehicles] + [math.nan] * len(walkers))
    c, s = np.cos(th)[:, None], np.sin(th)[:, None]
    dx, dy = ox[None, :] - tx[:, None], oy[None, :] - ty[:, None]
    fwd, lat = dx * c + dy * s, dy * c - dx * s
    turn = np.abs((oh[None, :] - th[:, None] + math.pi) % (2 * math.pi) - math.pi)
    same_way = np.isnan(oh)[None, :] | (turn < math.radians(45.0))
    ids = np.array([v[0] for v in vehicles] + [""] * len(walkers))
    other = ids[None, :] != np.array([t.id for t in traffic])[:, None]
    hit = (fwd > 0.5) & (fwd < reach[:, None]) & (np.abs(lat) < 2.0) & same_way & other
    return [bool(b) for b in hit.any(axis=1)]


def _box_occupied(city: City, node: str, vehicles: list[Vehicle], me: str) -> bool:
    n = city.intersection(node)
    w = ROAD_HALF - 1.0     # centre well inside: cars waiting at the box edge do not count
    return any(v != me and abs(x - n.x) < w and abs(y - n.y) < w for v, x, y, _ in vehicles)


def step_traffic(city: City, t: Traffic, paths: dict[Key, Polyline], rng: random.Random,
                 dt: float, vehicles: list[Vehicle], ahead: bool, blocked: frozenset[str],
                 busy: set[str]) -> None:
    """Advance one traffic vehicle by dt [s] (see the module doc for its rules). `busy`: the
    intersections claimed by a traffic vehicle (turning through them, or committed to enter),
    kept up to date within the step, so two never use one box at once. `ahead`: its corridor
    is blocked (corridors_blocked)."""
    limit = city.config.speed_limit
    target = limit
    turn = t.key if t.key[0] == "turn" else t.exit
    if turn is not None and city.segment(turn[1]).ux != city.segment(turn[3]).ux:
        slow_down = (t.speed ** 2 - TURN_SPEED ** 2) / (2 * TRAFFIC_ACCEL) + 4.0
        if t.key[0] == "turn" or paths[t.key].length - t.s < slow_down:
            target = min(limit, TURN_SPEED)
    braking = t.speed * t.speed / (2 * TRAFFIC_BRAKE)
    stop = ahead
    if not stop and t.key[0] == "lane":
        remaining = paths[t.key].length - t.s
        if remaining < braking + 4.0 and not t.committed:
            node = node_of(city, t.key)
            stop = (node in busy or _box_occupied(city, node, vehicles, t.id)
                    or _exit_jammed(t, paths, vehicles))
            if not stop:
                t.committed = True
                busy.add(node)
    if stop:
        t.speed = max(0.0, t.speed - TRAFFIC_BRAKE * dt)
    elif t.speed > target:
        t.speed = max(target, t.speed - TRAFFIC_BRAKE * dt)
    else:
        t.speed = min(target, t.speed + TRAFFIC_ACCEL * dt)
    t.s += t.speed * dt
    while t.s > paths[t.key].length:
        t.s -= paths[t.key].length
        _next_piece(city, t, rng, blocked)
    if t.key[0] == "turn":
        busy.add(node_of(city, t.key))
    place_traffic(t, paths)


def _exit_jammed(t: Traffic, paths: dict[Key, Polyline], vehicles: list[Vehicle]) -> bool:
    """Don't block the box: the lane after the turn has a vehicle near its start."""
    if t.exit is None:
        return False
    lane = paths[("lane", t.exit[3], t.exit[4])]
    (sx, sy), heading = lane.points[0], lane.pose(0.0)[2]
    return any(v != t.id and math.hypot(x - sx, y - sy) < 8.0
               and abs(wrap(h - heading)) < 45.0 for v, x, y, h in vehicles)


def choose_exit(city: City, t: Traffic, rng: random.Random, blocked: frozenset[str]) -> None:
    """On a lane piece, pick the turn to take at its end (a random legal exit)."""
    seg = city.segment(t.key[1])
    options = exits(city, seg, t.key[2], blocked) or exits(city, seg, t.key[2], frozenset())
    nxt, nd = options[rng.randrange(len(options))]
    t.exit = ("turn", t.key[1], t.key[2], nxt.id, nd)


def _next_piece(city: City, t: Traffic, rng: random.Random, blocked: frozenset[str]) -> None:
    if t.key[0] == "turn":
        t.key, t.committed = ("lane", t.key[3], t.key[4]), False
        choose_exit(city, t, rng, blocked)
        return
    if t.exit is None or t.exit[3] in blocked:
        choose_exit(city, t, rng, blocked)
    t.key, t.exit = t.exit, None


