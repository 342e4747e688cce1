"""A small teleo world as a package of its own: a robot on a floor sorts coloured balls into
the bins of their colour (docs/tutorial-world.md walks through it).

world       BinsWorld: the floor on a pymunk space (BaseWorld does the World protocol's
            common half), its config and its snapshot
perception  perceive(snapshot, agent): the percepts of bins.tlp, a pure function
render      a PNG of a cycle (or a GIF of the run) for people and for `teleo view`

``DOMAIN`` is what the package's entry point (pyproject.toml, group ``teleo.worlds``) names.
"""

from __future__ import annotations

from typing import Any

from teleo_world_bins.perception import perceive
from teleo_world_bins.render import render
from teleo_world_bins.world import ACTIONS, EVENTS, BinsWorld, load_config
from world.domain import Domain, event_problem


def create(table: dict[str, Any], seed: int, agents: list[str]) -> BinsWorld:
    """A BinsWorld of the scenario's `[world]` table (raises ConfigError naming the key)."""
    return BinsWorld(load_config(table, seed), seed, agents)


def check_config(table: dict[str, Any], agents: list[str]) -> None:
    """Everything about the `[world]` table that can be checked before a run."""
    load_config(table, 0)


def check_event(event: Any) -> str:
    """What is wrong with an event's fields ("" when nothing)."""
    return event_problem(EVENTS, event)


def plot_panel(ax: Any, run: Any) -> bool:
    """`teleo plot`'s panel: how many balls are in their bin, over world time [s]."""
    rows = [(c, sum(n.get("balls_sorted", 0) for n in run.snapshots[c]["counters"].values()))
            for c in run.cycles]
    ax.step(run.t([c for c, _ in rows]), [n for _, n in rows], where="post", label="sorted")
    ax.set_ylabel("balls sorted")
    return bool(rows)


DOMAIN = Domain(
    "bins", "a robot sorts coloured balls into the bins of their colour (example plug-in)",
    create, perceive, render, check_config,
    violations=("wrong_bin",), event_kinds=EVENTS.kinds, achievements=("balls_sorted",),
    actions=ACTIONS, check_event=check_event, static_keys=("size", "bins"),
    plot=("balls in their bin", plot_panel))
