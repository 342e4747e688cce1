"""The office delivery world of seed 003 (ROGUE on Xavier): a floor of offices, conference
rooms and corridors, doors that can be closed or blocked, people, mail, faxes and coffee
that cools, and a robot that navigates the corridors and carries out high-level operations.

config      OfficeConfig and load_office_config (the `[world]` table of an office scenario)
floor       static geometry: rooms, corridors, doors, walls and the floor graph
routes      shortest routes over the floor graph (navigator and perceived distances)
physics     the pymunk space: walls, door leaves and carts, people, obstacles, robot bodies
robot       the robot's state and its navigator (goto, replanning, bumps, progress, faults)
operations  the commands: goto, acquire, deliver, observe, say, stop
events      injected events and faults (doors, people, coffee, obstacles, false success)
simulation  OfficeSim: the World protocol
snapshot    OfficeSnapshot: the frozen state of a cycle, plain-data round trip
perception  perceive(snapshot, agent): the robot's percepts (documented in percepts.md)
render      render_png / render_gif for people

``DOMAIN`` is this package's entry in the world's domain registry (world/domain.py).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from world.domain import Domain
from world.errors import ConfigError
from world.office import view
from world.pictures import is_animation

VIOLATIONS = ("bumps",)
ACHIEVEMENTS = ("deliveries", "acquisitions", "observations")
ACTIONS = ("*goto", "*acquire", "*deliver", "*observe", "*say", "*stop")  # what apply_actions knows
EVENT_KINDS = ("open", "close", "block", "move", "false-success", "cool", "item", "give",
               "occupants", "obstacle", "clear", "stall")   # world/office/events.py


def create(table: dict[str, Any], seed: int, agents: list[str]):
    """An OfficeSim of the `[world]` table with one robot per agent (raises ConfigError)."""
    from world.office.config import load_office_config
    from world.office.simulation import OfficeSim

    return OfficeSim(load_office_config(table), seed, agents)


def check_config(table: dict[str, Any], agents: list[str]) -> None:
    """Everything about the table that can be checked before a run: keys, the floor's layout,
    references between rooms, people and items, and that every robot start is an agent's."""
    from world.office.config import load_office_config
    from world.office.floor import build_floor

    config = load_office_config(table)
    build_floor(config)
    for start in config.robots:
        if start.agent not in agents:
            raise ConfigError(f"[world] robots: {start.agent!r} is not an agent of this run "
                              f"(agents: {', '.join(agents)})")
    clash = sorted(set(agents) & ({r.id for r in config.rooms} | {p.id for p in config.people}
                                  | {i.id for i in config.items}))
    if clash:
        raise ConfigError(f"[world] agent ids {clash} are also room, person or item ids")


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """The robot's percepts (world/office/percepts.md) from a snapshot dict."""
    from world.office.perception import perceive as from_snapshot
    from world.office.snapshot import OfficeSnapshot

    return from_snapshot(OfficeSnapshot.from_dict(snapshot), agent)


def check_event(event: Any) -> str:
    """What is wrong with an event's fields ("" when nothing): world/office/events.py EVENTS."""
    from world.domain import event_problem
    from world.office.events import EVENTS

    return event_problem(EVENTS, event)


def render(snapshots: Sequence[dict[str, Any]], path: Path, agent: str | None = None) -> int:
    """A PNG or JPEG of the last snapshot with the robot's path, or a GIF of them all (by
    suffix: world/pictures.py); returns the frames drawn."""
    from world.office.render import render_gif, render_png
    from world.office.snapshot import OfficeSnapshot

    snaps = [OfficeSnapshot.from_dict(s) for s in snapshots]
    if is_animation(path):
        render_gif(snaps, path, agent=agent)
        return len(snaps)
    render_png(snaps, path, agent=agent)
    return 1


DOMAIN = Domain("office", "office delivery (seed 003): rooms, corridors, doors, people, mail, "
                "faxes and coffee, a robot with high-level operations",
                create, perceive, render, check_config, VIOLATIONS, EVENT_KINDS, ACHIEVEMENTS,
                actions=ACTIONS, check_event=check_event,
                static_keys=("config",), scene=None,
                plot=(view.PLOT_TITLE, view.plot_panel))
