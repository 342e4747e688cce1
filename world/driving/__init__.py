"""The urban driving world of seed 000 ("An Illustrative Domain", Tables 3 and 4).

config      WorldConfig and load_world_config (the `[world]` table of a driving scenario)
city        static geometry: streets, segments, intersections, lane lines, buildings
simulation  Simulation: pymunk bodies, the agent cars' actions, traffic, pedestrians, events
snapshot    WorldSnapshot: the frozen state of a cycle, plain-data round trip
perception  perceive(snapshot, agent): the agent's percepts (documented in percepts.md)
navigation  route guidance for carried packages
render      render_png / render_gif for people

``DOMAIN`` is this package's entry in the world's domain registry (world/domain.py).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from world.domain import Domain
from world.driving import view
from world.errors import ConfigError
from world.pictures import is_animation

VIOLATIONS = ("pedestrian_hits", "vehicle_collisions", "off_road", "yellow_crossings",
              "speeding_cycles")
ACTIONS = ("*cruise", "*gas", "*brake", "*straighten", "*steer")  # what apply_actions knows
EVENT_KINDS = ("pedestrian", "block", "unblock", "package")


def create(table: dict[str, Any], seed: int, agents: list[str]):
    """A Simulation of the `[world]` table for these agent cars (raises ConfigError)."""
    from world.driving.config import load_world_config
    from world.driving.simulation import Simulation

    return Simulation(load_world_config(table), seed, agents)


def check_config(table: dict[str, Any], agents: list[str]) -> None:
    """Everything about the table that can be checked before a run starts: keys, streets,
    package addresses (a building must exist), car starts (each an agent's)."""
    from world.driving.city import build_city
    from world.driving.config import load_world_config
    from world.driving.injection import ID

    config = load_world_config(table)
    build_city(config)
    for p in config.packages:
        if not ID.fullmatch(p.id):
            raise ConfigError(f"[world] package {p.id!r:.40}: expected an id of letters, digits, "
                              "'_' or '-' (a letter first, at most 32), as programs name it")
        if p.owner not in agents:
            raise ConfigError(f"[world] package {p.id}: owner {p.owner!r} is not an agent of "
                              f"this run (agents: {', '.join(agents)})")
    for car in config.cars:
        if car.agent not in agents:
            raise ConfigError(f"[world] cars: {car.agent!r} is not an agent of this run "
                              f"(agents: {', '.join(agents)})")


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """The agent's percepts (Table 3's form) from a snapshot dict."""
    from world.driving.perception import perceive_dict

    return perceive_dict(snapshot, agent)


def render(snapshots: Sequence[dict[str, Any]], path: Path, agent: str | None = None) -> int:
    """A PNG of the last snapshot with the agent's path, or a GIF of them all (by suffix);
    returns the frames drawn."""
    from world.driving.render import agent_trail, render_gif, render_png
    from world.driving.snapshot import WorldSnapshot

    snaps = [WorldSnapshot.from_dict(s) for s in snapshots]
    if is_animation(path):
        render_gif(snaps, path, agent=agent)
        return len(snaps)
    render_png(snaps[-1], path, agent=agent, trail=agent_trail(snaps, agent))
    return 1


def check_event(event: Any) -> str:
    """What is wrong with an event's fields ("" when nothing): world/driving/injection.py EVENTS."""
    from world.domain import event_problem
    from world.driving.injection import EVENTS

    return event_problem(EVENTS, event)


def restore(blob: bytes):
    """The Simulation saved by its `checkpoint()` (world/domain.py, restart)."""
    from world.driving.simulation import restore as restore_simulation

    return restore_simulation(blob)


DOMAIN = Domain("driving", "urban driving (seed 000): a city, traffic, pedestrians, packages",
                create, perceive, render, check_config, VIOLATIONS, EVENT_KINDS, ("deliveries",),
                restore=restore, actions=ACTIONS, check_event=check_event,
                static_keys=("config",), scene=view.scene,
                plot=(view.PLOT_TITLE, view.plot_panel))
