"""Helpers for the world tests: hand-built snapshots in a small quiet city."""

from __future__ import annotations

from world.driving.config import WorldConfig
from world.driving.snapshot import CarState, PackageState, PedState, WorldSnapshot

QUIET = WorldConfig(pedestrians=0, traffic=0, perception_range=50.0)


def snapshot(me: CarState, *others: CarState, peds: tuple[PedState, ...] = (),
             packages: tuple[PackageState, ...] = (), config: WorldConfig = QUIET,
             blocked: tuple[str, ...] = ()) -> WorldSnapshot:
    return WorldSnapshot(cycle=7, time=0.7, config=config, cars=(me, *others), pedestrians=peds,
                         packages=packages, blocked=blocked)


def car(x: float, y: float, heading: float, speed: float = 10.0, ident: str = "ME",
        kind: str = "agent") -> CarState:
    return CarState(ident, kind, x, y, heading, speed)
