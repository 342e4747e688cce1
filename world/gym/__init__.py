"""The Gymnasium world: environments others made (MiniGrid's procedurally generated grid
tasks first) as a teleo domain, `[world] domain = "gymnasium"` (docs/minigrid.md).

config      GymConfig and load_gym_config: `env` (a registered id) and `env_kwargs`
families    the families with a perception, keyed by name (minigrid)
paths       shortest paths for a grid agent with a heading: the affordances perception gives
simulation  GymWorld: the World protocol on one environment, one action a cycle, episodes
render      the environment's own frames (MiniGrid's tile renderer) as PNG, JPEG or GIF

``DOMAIN`` is this package's entry in the world's domain registry (world/domain.py).
"""

from __future__ import annotations

import pickle
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from world.domain import Domain
from world.errors import ConfigError, WorldError
from world.gym.families.minigrid import ACTIONS as _MINIGRID_ACTIONS

VIOLATIONS = ("lava", "collisions")
ACHIEVEMENTS = ("missions",)
ACTIONS = tuple("*" + a for a in _MINIGRID_ACTIONS) + ("*wait",)


def create(table: dict[str, Any], seed: int, agents: list[str]):
    """A GymWorld of the `[world]` table, its episode reset with `seed` (raises ConfigError)."""
    from world.gym.config import load_gym_config
    from world.gym.simulation import GymWorld

    return GymWorld(load_gym_config(table), seed, agents)


def check_config(table: dict[str, Any], agents: list[str]) -> None:
    """The env id is registered, of a family with a perception, and makes an episode with
    its env_kwargs; one agent."""
    create(table, 0, agents)


def restore(blob: bytes):
    """The inverse of GymWorld.checkpoint."""
    return pickle.loads(blob)


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """The agent's percepts from a snapshot dict, by the family of its environment."""
    from world.gym.families import FAMILIES, family

    state = snapshot.get("state")
    if not isinstance(state, dict) or state.get("family") not in FAMILIES:
        raise WorldError(f"gymnasium: perceive: a snapshot without the state of a known "
                         f"family ({', '.join(FAMILIES)})")
    if agent != snapshot.get("agent"):
        raise WorldError(f"gymnasium: perceive: unknown agent {agent!r} (the environment's "
                         f"agent is {snapshot.get('agent')!r})")
    return family(state["family"]).perceive(state, agent, snapshot.get("episode") or {})


def render(snapshots: Sequence[dict[str, Any]], path: Path, agent: str | None = None) -> int:
    """The environment's own frame of the last snapshot (PNG, JPEG), or of them all (GIF);
    returns the frames drawn."""
    from world.gym.render import render_frames

    return render_frames(snapshots, path)


DOMAIN = Domain("gymnasium", "a Gymnasium environment (MiniGrid's grid tasks): one agent, "
                "one action a cycle, one episode a run", create, perceive, render,
                check_config, VIOLATIONS, (), ACHIEVEMENTS, restore=restore, actions=ACTIONS)

__all__ = ["DOMAIN", "ConfigError"]
