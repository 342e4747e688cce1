"""Static city geometry built from a WorldConfig: streets, segments, intersections, lane lines,
buildings with addresses and their curb points. Pure and cached per config.

Layout (seed 000, "An Illustrative Domain"): lettered streets run north-south at x = i * L,
ordinal streets east-west at y = j * L (L = block length [m]). A segment is one block of a street
between two intersections; its axis points toward increasing x (east) or y (north). Across the
axis (lateral offset, + = left of the axis direction) lie the five lane lines:
yellow at 0, white at +-LANE_WIDTH, sidewalk lines (the curbs) at +-ROAD_HALF.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property, lru_cache

from world.driving.config import WorldConfig
from world.errors import ConfigError, WorldError

LANE_WIDTH = 4.0        # [m] yellow line to white line
ROAD_HALF = 6.0         # [m] yellow line to curb (sidewalk line); road = |lateral| <= ROAD_HALF
LANE_CENTRE = 2.0       # [m] centre of the right lane from the yellow line
CURB_OFFSET = 5.0       # [m] lateral offset of an address's curb (delivery) point
WALK_OFFSET = 7.5       # [m] pedestrians walk here on the sidewalk
SIDEWALK_OUTER = 9.0    # [m] outer edge of the sidewalk
BUILDING_NEAR, BUILDING_FAR = 11.0, 25.0   # [m] building front and back from the street axis
CORNER_MARGIN = 26.0    # [m] no buildings this close (along the street) to an intersection centre
LINES = (("YELLOW", "YELLOW", 0.0), ("WHITE1", "WHITE", LANE_WIDTH),
         ("WHITE2", "WHITE", -LANE_WIDTH), ("SIDEWALK1", "SIDEWALK", ROAD_HALF),
         ("SIDEWALK2", "SIDEWALK", -ROAD_HALF))


@dataclass(frozen=True)
class Intersection:
    id: str
    x: float
    y: float
    ew: str        # the east-west (ordinal) street through it
    ns: str        # the north-south (lettered) street through it
    col: int
    row: int


@dataclass(frozen=True)
class Segment:
    id: str
    street: str
    start: str     # intersection id at the axis start
    end: str       # intersection id at the axis end
    x0: float
    y0: float
    ux: float      # unit axis direction (east or north)
    uy: float
    length: float  # centre to centre [m]

    def local(self, x: float, y: float) -> tuple[float, float]:
        """(along from the start centre, lateral + = left of the axis) of a world point [m]."""
        dx, dy = x - self.x0, y - self.y0
        return dx * self.ux + dy * self.uy, -dx * self.uy + dy * self.ux

    def point(self, along: float, lateral: float) -> tuple[float, float]:
        """World point at (along, lateral) [m]."""
        return (self.x0 + along * self.ux - lateral * self.uy,
                self.y0 + along * self.uy + lateral * self.ux)

    @property
    def heading(self) -> float:
        """Axis direction [deg], 0 = east, 90 = north."""
        return math.degrees(math.atan2(self.uy, self.ux))


@dataclass(frozen=True)
class Building:
    id: str
    street: str
    address: int
    segment: str
    side: int                                  # +1 left of the segment axis, -1 right
    corners: tuple[tuple[float, float], ...]   # four [m]
    curb: tuple[float, float]                  # delivery point on the road shoulder [m]
    along: float                               # curb point along the segment [m]

    @cached_property
    def disc(self) -> tuple[float, float, float]:
        """A disc holding the corners, (centre x, centre y, radius) [m]: perception passes
        over a building whose disc is out of range without trigonometry."""
        cx = sum(x for x, _ in self.corners) / len(self.corners)
        cy = sum(y for _, y in self.corners) / len(self.corners)
        return cx, cy, max(math.hypot(x - cx, y - cy) for x, y in self.corners)


@dataclass(frozen=True, eq=False)
class City:
    config: WorldConfig
    intersections: tuple[Intersection, ...]
    segments: tuple[Segment, ...]
    buildings: tuple[Building, ...]
    by_node: dict[str, tuple[Segment, ...]] = field(default_factory=dict)
    by_address: dict[tuple[str, int], Building] = field(default_factory=dict)

    @property
    def size(self) -> tuple[float, float]:
        """Extent of the street grid [m] (x, y)."""
        L = self.config.block_length
        return (len(self.config.ns_streets) - 1) * L, (len(self.config.ew_streets) - 1) * L

    def segment(self, seg_id: str) -> Segment:
        try:
            return self.segments[_index(seg_id, "S")]
        except (IndexError, ValueError):
            raise WorldError(f"unknown segment {seg_id!r}") from None

    def intersection(self, node_id: str) -> Intersection:
        try:
            return self.intersections[_index(node_id, "I")]
        except (IndexError, ValueError):
            raise WorldError(f"unknown intersection {node_id!r}") from None

    def node_at(self, col: int, row: int) -> Intersection:
        return self.intersections[row * len(self.config.ns_streets) + col]

    def segment_between(self, a: str, b: str) -> Segment:
        for seg in self.by_node[a]:
            if {seg.start, seg.end} == {a, b}:
                return seg
        raise WorldError(f"no segment between {a} and {b}")

    def segments_at(self, node_id: str) -> tuple[Segment, ...]:
        """Segments that start or end at an intersection."""
        return self.by_node[node_id]

    def building(self, street: str, address: int) -> Building:
        b = self.by_address.get((street, address))
        if b is None:
            raise WorldError(f"no building with address {address} on street {street}")
        return b

    def locate(self, x: float, y: float) -> tuple[str, str | None, float, float]:
        """Road element under a point: ("intersection", id, 0, 0), ("segment", id, along,
        lateral) or ("off", None, 0, 0). O(1) on the grid."""
        L, W = self.config.block_length, ROAD_HALF
        nc, nr = len(self.config.ns_streets), len(self.config.ew_streets)
        i, j = round(x / L), round(y / L)
        dx, dy = x - i * L, y - j * L
        if 0 <= i < nc and 0 <= j < nr and abs(dx) <= W and abs(dy) <= W:
            return "intersection", self.node_at(i, j).id, 0.0, 0.0
        if 0 <= j < nr and abs(dy) <= W and 0 <= x <= (nc - 1) * L:
            seg = self.segment(_ew_id(min(int(x // L), nc - 2), j, nc))
            along, lat = seg.local(x, y)
            return "segment", seg.id, along, lat
        if 0 <= i < nc and abs(dx) <= W and 0 <= y <= (nr - 1) * L:
            seg = self.segment(_ns_id(i, min(int(y // L), nr - 2), nc, nr))
            along, lat = seg.local(x, y)
            return "segment", seg.id, along, lat
        return "off", None, 0.0, 0.0


def _index(ident: str, prefix: str) -> int:
    if not ident.startswith(prefix):
        raise ValueError(ident)
    k = int(ident[len(prefix):]) - 1
    if k < 0:
        raise ValueError(ident)
    return k


def _ew_id(col: int, row: int, nc: int) -> str:
    return f"S{row * (nc - 1) + col + 1}"


def _ns_id(col: int, row: int, nc: int, nr: int) -> str:
    return f"S{nr * (nc - 1) + col * (nr - 1) + row + 1}"


def _segments_by_node(nodes: tuple[Intersection, ...], segs: list[Segment]) -> dict:
    out: dict[str, list[Segment]] = {n.id: [] for n in nodes}
    for seg in segs:
        out[seg.start].append(seg)
        out[seg.end].append(seg)
    return {k: tuple(v) for k, v in out.items()}


@lru_cache(maxsize=32)
def build_city(config: WorldConfig) -> City:
    """The static city of a config (cached: perception calls it every cycle)."""
    L = config.block_length
    ns, ew = config.ns_streets, config.ew_streets
    nc, nr = len(ns), len(ew)
    nodes = tuple(Intersection(f"I{j * nc + i + 1}", i * L, j * L, ew[j], ns[i], i, j)
                  for j in range(nr) for i in range(nc))
    segs: list[Segment] = []
    for j in range(nr):
        for i in range(nc - 1):
            segs.append(Segment(_ew_id(i, j, nc), ew[j], nodes[j * nc + i].id,
                                nodes[j * nc + i + 1].id, i * L, j * L, 1.0, 0.0, L))
    for i in range(nc):
        for j in range(nr - 1):
            segs.append(Segment(_ns_id(i, j, nc, nr), ns[i], nodes[j * nc + i].id,
                                nodes[(j + 1) * nc + i].id, i * L, j * L, 0.0, 1.0, L))
    segs.sort(key=lambda s: _index(s.id, "S"))
    buildings = _buildings(segs, L)
    city = City(config, nodes, tuple(segs), buildings, _segments_by_node(nodes, segs),
                {(b.street, b.address): b for b in buildings})
    _check_packages(city)
    return city


def _buildings(segs: list[Segment], L: float) -> tuple[Building, ...]:
    """Two buildings per side per segment; addresses per street: odd on the left of the axis,
    even on the right, increasing along the axis (1, 3, 5 ... and 2, 4, 6 ...)."""
    usable = L - 2 * CORNER_MARGIN
    width = (usable - 4.0) / 2
    out: list[Building] = []
    counters: dict[tuple[str, int], int] = {}
    for seg in segs:   # segments are in street order along the axis within each street
        for k in range(2):
            a0 = CORNER_MARGIN + k * (width + 4.0)
            a1 = a0 + width
            for side in (1, -1):
                n = counters.get((seg.street, side), 0)
                counters[(seg.street, side)] = n + 1
                address = 2 * n + (1 if side == 1 else 2)
                corners = tuple(seg.point(a, side * d) for a, d in
                                ((a0, BUILDING_NEAR), (a1, BUILDING_NEAR),
                                 (a1, BUILDING_FAR), (a0, BUILDING_FAR)))
                mid = (a0 + a1) / 2
                out.append(Building(f"B{len(out) + 1}", seg.street, address, seg.id, side,
                                    corners, seg.point(mid, side * CURB_OFFSET), mid))
    return tuple(out)


def _check_packages(city: City) -> None:
    index = {(b.street, b.address) for b in city.buildings}
    for p in city.config.packages:
        if (p.street, p.address) not in index:
            raise ConfigError(f"[world] package {p.id}: no address {p.address} on {p.street}")
