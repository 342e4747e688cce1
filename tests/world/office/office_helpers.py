"""Helpers for the office world's tests: a world on the default floor and a loop that sends a
command every cycle, as a teleoreactive program does, until its operation ends."""

from __future__ import annotations

from typing import Any

from world.domain import get_domain

OFFICE = get_domain("office")


def office(table: dict[str, Any] | None = None, seed: int = 1, agents: tuple[str, ...] = ("ME",)):
    """An office world (the default floor unless `table` says otherwise)."""
    return OFFICE.create(dict(table or {}), seed, list(agents))


def until_done(world, command: list[Any], agent: str = "ME", limit: int = 400,
               every_cycle: bool = False) -> tuple[int, dict[str, Any]]:
    """Send `command` (once, or every cycle as a teleoreactive program does) and step until
    an outcome of it arrives. Returns (cycles stepped, that first outcome)."""
    outcomes = world.apply_actions(agent, [command])
    for cycles in range(limit + 1):
        mine = [o for o in outcomes if o["action"] == list(command)]
        if mine:
            return cycles, mine[0]
        world.step()
        outcomes = world.apply_actions(agent, [command] if every_cycle else [])
    raise AssertionError(f"{command} did not end within {limit} cycles")


def robot(world, agent: str = "ME") -> dict[str, Any]:
    """The robot's state in the current snapshot."""
    return next(r for r in world.snapshot_dict()["robots"] if r["id"] == agent)


def percepts(world, agent: str = "ME", kind: str | None = None) -> list[list[Any]]:
    snap = world.snapshot_dict()
    return [p for p in OFFICE.perceive(snap, agent) if kind is None or p[0] == kind]


def percept(world, kind: str, ident: str, agent: str = "ME") -> dict[str, Any]:
    """One percept as a dict of its attributes."""
    for p in percepts(world, agent, kind):
        if p[1] == ident:
            return dict(zip(p[2::2], p[3::2], strict=True))
    raise AssertionError(f"no percept ({kind} {ident})")


def events(world, kind: str) -> list[dict[str, Any]]:
    return [e for e in world.snapshot_dict()["events"] if e["kind"] == kind]
