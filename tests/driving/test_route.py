"""Route choice in the program (programs/driving.tlp, concept `route`): from the map percepts
and the package's lane, the car reaches every address of the city, by a route at most a loop
longer than the shortest. Inference only: the car is put on each segment the route chooses."""

from __future__ import annotations

from collections import deque

import pytest

from agents.lang import Engine, load_program
from tests.driving.scenarios import PROGRAM
from world.driving.city import build_city
from world.driving.config import WorldConfig
from world.driving.navigation import exits, target_edge
from world.driving.perception import perceive
from world.driving.snapshot import CarState, PackageState, WorldSnapshot

CONFIG = WorldConfig(pedestrians=0, traffic=0)
CITY = build_city(CONFIG)
ENGINE = Engine(load_program(PROGRAM))
STARTS = (("S16", 1), ("S7", -1), ("S24", -1))     # B north from FIRST, SECOND west, D south


def place(seg_id: str, d: int, along_edge: float) -> CarState:
    """A car in the right lane of directed edge (seg, d), ``along_edge`` m from its start."""
    seg = CITY.segment(seg_id)
    along = along_edge if d > 0 else seg.length - along_edge
    x, y = seg.point(along, -2.0 * d)
    return CarState("ME", "agent", x, y, seg.heading if d > 0 else seg.heading - 180.0, 8.0)


def shortest(start: tuple[str, int], goal: tuple[str, int]) -> int:
    """Fewest intersections passed from the start edge to the goal edge (no U-turns)."""
    seen, todo = {start: 0}, deque([start])
    while todo:
        edge = todo.popleft()
        if edge == goal:
            return seen[edge]
        for seg, d in exits(CITY, CITY.segment(edge[0]), edge[1], frozenset()):
            if (seg.id, d) not in seen:
                seen[(seg.id, d)] = seen[edge] + 1
                todo.append((seg.id, d))
    raise AssertionError(f"{goal} unreachable from {start}")


def beliefs(edge: tuple[str, int], along: float, package: PackageState):
    snap = WorldSnapshot(0, 0.0, CONFIG, (place(*edge, along),), (), (package,))
    return ENGINE.infer(perceive(snap, "ME"))


def follow(start: tuple[str, int], street: str, address: int) -> int:
    """Intersections passed until the address is in front (seen 5 m into a segment); the car
    is moved onto each exit the program chooses (60 m into a segment, the exits in sight)."""
    package = PackageState("P", address, street, "ME")
    edge, hops = start, 0
    while hops < 20:
        seen = {str(b) for b in beliefs(edge, 5.0, package)}
        if hops and f"(address-in-front ME {address} {street})" in seen:
            return hops
        routes = [b for b in beliefs(edge, 60.0, package) if b.pred == "route"]
        assert len(routes) == 1, (edge, street, address, routes)
        _, _, _, node, seg_id = routes[0].args
        seg = CITY.segment(seg_id)
        edge, hops = (seg_id, 1 if seg.start == node else -1), hops + 1
    raise AssertionError(f"no arrival at {address} {street} from {start} in 20 intersections")


@pytest.mark.parametrize("start", STARTS)
def test_every_address_is_reached_by_a_short_route(start):
    extra = []
    for b in CITY.buildings:
        goal = target_edge(b)
        hops = follow(start, b.street, b.address)
        best = shortest(start, goal) if start != goal else 0
        assert hops <= best + 4, (b.street, b.address, hops, best)
        extra.append(hops - best)
    assert min(extra) >= 0
    assert sum(1 for e in extra if e > 0) <= len(extra) // 10   # mostly the shortest route
