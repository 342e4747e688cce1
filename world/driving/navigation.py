"""Route guidance for carried packages (the car's navigation system): the turn to take at the
next intersection ahead on a shortest legal route to an address. Pure.

Routes follow the streets in the driving direction; U-turns are never planned. A directed edge
(segment, +1|-1) is a segment travelled along (+1) or against (-1) its axis. An address is reached
on the directed edge that has its building on the right (right-hand traffic).
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass

from world.driving.city import Building, City, Segment

ARRIVE_BEHIND = 10.0   # [m] an address this far behind the car still counts as ARRIVING
_WITHIN_45 = math.cos(math.radians(45.0)) - 1e-12   # |cos| of a heading within 45 deg of an axis


@dataclass(frozen=True)
class Guidance:
    turn: str        # "LEFT" | "RIGHT" | "STRAIGHT" | "ARRIVING" | "NONE" (unreachable)
    dist: float      # [m] to the turn's intersection centre, or along the street to the address


def target_edge(b: Building) -> tuple[str, int]:
    """The directed edge that has building b on its right."""
    return b.segment, -b.side


def edge_end(seg: Segment, d: int) -> str:
    return seg.end if d > 0 else seg.start


def turn_kind(seg_in: Segment, d_in: int, seg_out: Segment, d_out: int) -> str:
    """LEFT / RIGHT / STRAIGHT for leaving seg_in (direction d_in) into seg_out (d_out)."""
    ax, ay = seg_in.ux * d_in, seg_in.uy * d_in
    bx, by = seg_out.ux * d_out, seg_out.uy * d_out
    cross = ax * by - ay * bx
    if abs(cross) < 1e-9:
        return "STRAIGHT"
    return "LEFT" if cross > 0 else "RIGHT"


def exits(city: City, seg: Segment, d: int, blocked: frozenset[str]) -> list[tuple[Segment, int]]:
    """Directed edges leaving the end of (seg, d), without the U-turn and blocked segments."""
    node = edge_end(seg, d)
    out = []
    for nxt in city.segments_at(node):
        if nxt.id == seg.id or nxt.id in blocked:
            continue
        out.append((nxt, 1 if nxt.start == node else -1))
    return out


def guide(city: City, seg: Segment, d: int, along: float, building: Building,
          blocked: frozenset[str] = frozenset()) -> Guidance:
    """Guidance for a car at `along` [m] on directed edge (seg, d) toward a building's curb."""
    tseg, td = target_edge(building)
    travelled = along if d > 0 else seg.length - along          # [m] from the edge's start
    if (seg.id, d) == (tseg, td):
        ahead = (building.along - along) * d
        if ahead > -ARRIVE_BEHIND:
            return Guidance("ARRIVING", round(ahead, 3))
    to_node = seg.length - travelled
    first = _first_hop(city, seg, d, tseg, td, building, blocked)
    if first is None:
        return Guidance("NONE", round(to_node, 3))
    return Guidance(turn_kind(seg, d, *first), round(to_node, 3))


def _first_hop(city: City, seg: Segment, d: int, tseg: str, td: int, building: Building,
               blocked: frozenset[str]) -> tuple[Segment, int] | None:
    """Dijkstra over directed edges from the end of (seg, d); returns the first edge taken."""
    target_cost = building.along if td > 0 else city.segment(tseg).length - building.along
    heap: list[tuple[float, int, str, int, str, int]] = []
    order = 0
    for nxt, nd in exits(city, seg, d, blocked):
        order += 1
        heapq.heappush(heap, (0.0, order, nxt.id, nd, nxt.id, nd))
    seen: set[tuple[str, int]] = set()
    while heap:
        cost, _, sid, sd, fid, fd = heapq.heappop(heap)
        if (sid, sd) in seen:
            continue
        seen.add((sid, sd))
        cur = city.segment(sid)
        if (sid, sd) == (tseg, td):
            return city.segment(fid), fd
        for nxt, nd in exits(city, cur, sd, blocked):
            if (nxt.id, nd) not in seen:
                order += 1
                step = target_cost if (nxt.id, nd) == (tseg, td) else nxt.length
                heapq.heappush(heap, (cost + step, order, nxt.id, nd, fid, fd))
    return None


def aligned_segment(city: City, x: float, y: float, heading: float,
                    lookahead: float = 5.0) -> tuple[Segment, int] | None:
    """The nearest segment whose axis is within 45 deg of the heading [deg], with the direction of
    travel on it (+1 along the axis, -1 against). Distance is measured from a point `lookahead`
    [m] ahead of the car to the segment's axis, so inside an intersection the street being
    entered wins over the one being left."""
    h = math.radians(heading)
    hx, hy = math.cos(h), math.sin(h)
    px, py = x + lookahead * hx, y + lookahead * hy
    best: tuple[float, int, Segment, int] | None = None
    for k, seg in enumerate(city.segments):
        dot = hx * seg.ux + hy * seg.uy
        if abs(dot) < _WITHIN_45:
            continue
        along, lat = seg.local(px, py)
        off = max(0.0, -along, along - seg.length)
        dist = math.hypot(off, lat)
        if best is None or (dist, k) < best[:2]:
            best = (dist, k, seg, 1 if dot > 0 else -1)
    return None if best is None else (best[2], best[3])


def current_edge(city: City, x: float, y: float, heading: float) -> tuple[Segment, int] | None:
    """The directed edge the car is on, for route guidance. On a segment: that segment, in the
    direction of the heading. Inside an intersection: the edge that enters it in the direction
    of the heading (so the advice stays about this intersection until the car has left it), or
    the one that leaves it where none enters. Elsewhere: the aligned segment."""
    kind, where, _, _ = city.locate(x, y)
    h = math.radians(heading)
    hx, hy = math.cos(h), math.sin(h)
    limit = _WITHIN_45
    if kind == "segment":
        seg = city.segment(where)
        dot = hx * seg.ux + hy * seg.uy
        if abs(dot) >= limit:
            return seg, 1 if dot > 0 else -1
    elif kind == "intersection":
        best: tuple[tuple[int, float, str], Segment, int] | None = None
        for seg in city.segments_at(where):
            dot = hx * seg.ux + hy * seg.uy
            if abs(dot) < limit:
                continue
            d = 1 if dot > 0 else -1
            key = (0 if edge_end(seg, d) == where else 1, -abs(dot), seg.id)
            if best is None or key < best[0]:
                best = (key, seg, d)
        if best is not None:
            return best[1], best[2]
    return aligned_segment(city, x, y, heading)
