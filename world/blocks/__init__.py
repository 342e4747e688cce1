"""The Blocks World of seed 000 (Figure 3): a table, blocks of given sizes, a gripper per agent.

config      BlocksConfig and load_blocks_config (the `[world]` table of a blocks scenario)
towers      random towers drawn from a seed
table       the static table, floor and walls
block       a block's pymunk body and its box geometry
gripper     an agent's gripper (hand) and its counters
actions     *pickup *unstack *putdown *stack (*wait): done in one cycle or refused with a reason
events      add, remove, knock, slip
simulation  BlocksWorld: the World protocol on a pymunk space
snapshot    BlocksSnapshot: the frozen state of a cycle, plain-data round trip
perception  perceive(snapshot, agent): programs/blocks.tlp's percepts (percepts.md)
render      render_png / render_gif for people

``DOMAIN`` is this package's entry in the world's domain registry (world/domain.py).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from world.blocks import view
from world.domain import Domain
from world.errors import ConfigError
from world.pictures import is_animation

VIOLATIONS = ("blocks_dropped",)
ACHIEVEMENTS = ("blocks_moved",)
ACTIONS = ("*pickup", "*unstack", "*putdown", "*stack", "*wait")  # what apply_actions knows
EVENT_KINDS = ("add", "remove", "knock", "slip")


def create(table: dict[str, Any], seed: int, agents: list[str]):
    """A BlocksWorld of the `[world]` table for these agents (raises ConfigError)."""
    from world.blocks.config import load_blocks_config
    from world.blocks.simulation import BlocksWorld

    check_config(table, agents)
    return BlocksWorld(load_blocks_config(table, seed), seed, agents)


def check_config(table: dict[str, Any], agents: list[str]) -> None:
    """Everything about the table that can be checked before a run: keys, sizes, towers that
    fit the table, held blocks of agents of this run."""
    from world.blocks.config import load_blocks_config

    config = load_blocks_config(table)
    for agent in sorted(config.holding):
        if agent not in agents:
            raise ConfigError(f"[world] holding.{agent}: not an agent of this run "
                              f"(agents: {', '.join(agents)})")


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """The agent's percepts (programs/blocks.tlp's form) from a snapshot dict."""
    from world.blocks.perception import perceive as from_snapshot

    return from_snapshot(snapshot, agent)


def check_event(event: Any) -> str:
    """What is wrong with an event's fields ("" when nothing): world/blocks/events.py EVENTS."""
    from world.blocks.events import EVENTS
    from world.domain import event_problem

    return event_problem(EVENTS, event)


def render(snapshots: Sequence[dict[str, Any]], path: Path, agent: str | None = None) -> int:
    """A PNG or JPEG of the last snapshot, or a GIF of them all (by suffix:
    world/pictures.py); returns the frames drawn."""
    from world.blocks.render import render_gif, render_png
    from world.blocks.snapshot import BlocksSnapshot

    snaps = [BlocksSnapshot.from_dict(s) for s in snapshots]
    if is_animation(path):
        render_gif(snaps, path, agent=agent)
        return len(snaps)
    render_png(snaps[-1], path, agent=agent)
    return 1


DOMAIN = Domain("blocks", "the Blocks World (seed 000, Figure 3): a table, blocks, a gripper "
                "per agent", create, perceive, render, check_config, VIOLATIONS, EVENT_KINDS,
                ACHIEVEMENTS, actions=ACTIONS, check_event=check_event,
                static_keys=("table", "resolution"), scene=view.scene,
                plot=(view.PLOT_TITLE, view.plot_panel))
