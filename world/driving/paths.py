"""Lane paths that simulator-driven traffic follows: one straight piece per directed edge (the
right lane between the intersection boxes) and one curve per allowed turn (a quadratic Bezier
through the intersection). Pure, cached per city."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from world.driving.city import LANE_CENTRE, ROAD_HALF, City, Segment
from world.driving.navigation import edge_end, exits

Edge = tuple[str, int]
Key = tuple  # ("lane", seg, d) or ("turn", seg_in, d_in, seg_out, d_out)


@dataclass(frozen=True)
class Polyline:
    points: tuple[tuple[float, float], ...]
    cum: tuple[float, ...]        # cumulative length [m] at each point

    @property
    def length(self) -> float:
        return self.cum[-1]

    def pose(self, s: float) -> tuple[float, float, float]:
        """(x, y, heading [deg]) at arc length s [m] (clamped to the ends)."""
        s = min(max(s, 0.0), self.length)
        k = 1
        while k < len(self.cum) - 1 and self.cum[k] < s:
            k += 1
        (x0, y0), (x1, y1) = self.points[k - 1], self.points[k]
        span = self.cum[k] - self.cum[k - 1]
        t = 0.0 if span <= 0 else (s - self.cum[k - 1]) / span
        return x0 + t * (x1 - x0), y0 + t * (y1 - y0), math.degrees(math.atan2(y1 - y0, x1 - x0))


def polyline(points: list[tuple[float, float]]) -> Polyline:
    cum = [0.0]
    for (x0, y0), (x1, y1) in zip(points, points[1:], strict=False):
        cum.append(cum[-1] + math.hypot(x1 - x0, y1 - y0))
    return Polyline(tuple(points), tuple(cum))


def lane_ends(seg: Segment, d: int) -> tuple[tuple[float, float], tuple[float, float]]:
    """Start and end of the right lane of a directed edge, at the intersection box edges."""
    lat = -LANE_CENTRE * d           # right of the travel direction
    a0, a1 = (ROAD_HALF, seg.length - ROAD_HALF)
    if d < 0:
        a0, a1 = a1, a0
    return seg.point(a0, lat), seg.point(a1, lat)


def _turn(city: City, e_in: tuple[Segment, int], e_out: tuple[Segment, int]) -> Polyline:
    p0 = lane_ends(*e_in)[1]
    p2 = lane_ends(*e_out)[0]
    (si, di), (so, do) = e_in, e_out
    ax, ay = si.ux * di, si.uy * di
    bx, by = so.ux * do, so.uy * do
    den = ax * by - ay * bx
    if abs(den) < 1e-9:
        return polyline([p0, p2])
    # control point: where the incoming and outgoing lane lines meet
    t = ((p2[0] - p0[0]) * by - (p2[1] - p0[1]) * bx) / den
    c = (p0[0] + t * ax, p0[1] + t * ay)
    pts = []
    for k in range(9):
        u = k / 8
        pts.append(((1 - u) ** 2 * p0[0] + 2 * u * (1 - u) * c[0] + u * u * p2[0],
                    (1 - u) ** 2 * p0[1] + 2 * u * (1 - u) * c[1] + u * u * p2[1]))
    return polyline(pts)


@lru_cache(maxsize=16)
def lane_paths(city: City) -> dict[Key, Polyline]:
    """Every lane and turn piece of a city, keyed as described in the module doc."""
    out: dict[Key, Polyline] = {}
    for seg in city.segments:
        for d in (1, -1):
            out[("lane", seg.id, d)] = polyline(list(lane_ends(seg, d)))
            for nxt, nd in exits(city, seg, d, frozenset()):
                out[("turn", seg.id, d, nxt.id, nd)] = _turn(city, (seg, d), (nxt, nd))
    return out


def node_of(city: City, key: Key) -> str:
    """The intersection a lane piece runs toward, or a turn piece runs through."""
    return edge_end(city.segment(key[1]), key[2])
