"""The environment families the Gymnasium world has a perception for, keyed by family name;
an environment's family is found from its registered entry point's package (MiniGrid's
`minigrid.envs:DoorKeyEnv` is of family "minigrid"). A family module offers NAME, ACTIONS,
`capture(env)` (the state as plain data), `perceive(state, agent, episode)` (percepts, pure)
and `frame(state)` (the environment's own picture, an RGB array).
"""

from __future__ import annotations

import importlib
from types import ModuleType

FAMILIES = {"minigrid": "world.gym.families.minigrid"}   # family -> module
PACKAGES = {"minigrid": "minigrid"}                       # entry-point package -> family


def family_of_entry_point(entry_point: object) -> str | None:
    """The family of an environment registered with `entry_point` (a "pkg.mod:Class" string
    or a callable), or None when no family knows it."""
    text = entry_point if isinstance(entry_point, str) else \
        getattr(entry_point, "__module__", "") or ""
    return PACKAGES.get(text.split(":")[0].split(".")[0])


def family(name: str) -> ModuleType:
    """The module of family `name` (KeyError when unknown)."""
    return importlib.import_module(FAMILIES[name])
