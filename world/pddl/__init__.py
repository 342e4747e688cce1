"""A STRIPS world from PDDL: a scenario `[world] domain = "pddl"` with `domain_file`
and `problem_file`; the state is the problem's true atoms, perceived each cycle, and the agents'
ground actions are applied with PDDL semantics (docs/pddl.md, percepts.md).

task        the domain and problem read with the `pddl` package into frozen data, checked
convert     the library's objects to task.py's data; what the world refuses
semantics   one ground action on a state: preconditions, delete and add effects
config      the `[world]` table
simulation  PddlWorld: the World protocol
perception  perceive(snapshot, agent): one percept per atom and per object and type
render      a text panel of the state (PNG, GIF)
program     the teleo program of a domain (`teleo pddl program`)

``DOMAIN`` is this package's entry in the world's domain registry (world/domain.py).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from world.domain import Domain
from world.pictures import is_animation

ACHIEVEMENTS = ("actions_done",)


def create(table: dict[str, Any], seed: int, agents: list[str]):
    """A PddlWorld of the `[world]` table (raises ConfigError)."""
    from world.pddl.config import load_pddl_config
    from world.pddl.simulation import PddlWorld

    return PddlWorld(load_pddl_config(table), seed, agents)


def check_config(table: dict[str, Any], agents: list[str]) -> None:
    """Read and check both files (every error a ConfigError, one line)."""
    from world.pddl.config import load_pddl_config

    load_pddl_config(table)


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    from world.pddl.perception import perceive as from_snapshot

    return from_snapshot(snapshot, agent)


def render(snapshots: Sequence[dict[str, Any]], path: Path, agent: str | None = None) -> int:
    """A PNG or JPEG of the last snapshot, or a GIF of them all; returns the frames drawn."""
    from world.pddl.render import render_gif, render_png

    if is_animation(path):
        render_gif(list(snapshots), path, agent)
        return len(snapshots)
    render_png(snapshots[-1], path, agent)
    return 1


def restore(blob: bytes):
    from world.pddl.simulation import restore as from_blob

    return from_blob(blob)


DOMAIN = Domain("pddl", "a STRIPS world from a PDDL domain and problem (docs/pddl.md)", create,
                perceive, render, check_config, achievements=ACHIEVEMENTS, restore=restore)
