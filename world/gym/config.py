"""The `[world]` table of a Gymnasium scenario: `env` (a registered id, such as
"MiniGrid-DoorKey-8x8-v0", the default) and `env_kwargs` (a table passed to
gymnasium.make). Errors are one line naming the key and value, and the families known
(docs/minigrid.md)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from world.errors import ConfigError
from world.gym.families import FAMILIES, family_of_entry_point

_KNOWN = {"domain", "env", "env_kwargs"}
DEFAULT_ENV = "MiniGrid-DoorKey-8x8-v0"   # what an empty [world] table runs


@dataclass(frozen=True)
class GymConfig:
    """An environment id, its keyword arguments and its family (a key of FAMILIES)."""

    env: str
    family: str
    env_kwargs: dict[str, Any] = field(default_factory=dict)


def _known() -> str:
    return f"families known: {', '.join(sorted(FAMILIES))}"


def load_gym_config(table: dict[str, Any]) -> GymConfig:
    """The config of a `[world]` table; raises ConfigError naming the key."""
    extra = sorted(set(table) - _KNOWN)
    if extra:
        raise ConfigError(f"[world] {extra[0]}: unknown key for the gymnasium domain; "
                          f"known: {', '.join(sorted(_KNOWN - {'domain'}))}")
    env_id = table.get("env", DEFAULT_ENV)
    if not isinstance(env_id, str) or not env_id:
        raise ConfigError(f"[world] env: expected a registered environment id such as "
                          f"'MiniGrid-DoorKey-8x8-v0', got {env_id!r}")
    kwargs = table.get("env_kwargs", {})
    if not isinstance(kwargs, dict):
        raise ConfigError(f"[world] env_kwargs: expected a table, got {kwargs!r}")
    try:
        import gymnasium
        import minigrid  # noqa: F401  (registers the MiniGrid ids)
    except ImportError as exc:
        raise ConfigError(f"[world] env = {env_id!r}: the gymnasium domain needs the extra "
                          f"'gym' (pip install 'teleo[gym]'): {exc}") from exc
    try:
        spec = gymnasium.spec(env_id)
    except gymnasium.error.Error as exc:
        raise ConfigError(f"[world] env = {env_id!r}: not a registered environment "
                          f"({str(exc).splitlines()[0]}); {_known()}") from exc
    fam = family_of_entry_point(spec.entry_point)
    if fam is None:
        raise ConfigError(f"[world] env = {env_id!r}: no perception for its family "
                          f"(entry point {spec.entry_point!r}); {_known()}")
    return GymConfig(env_id, fam, dict(kwargs))


def make_env(config: GymConfig) -> Any:
    """gymnasium.make of the config (its unwrapped env is stepped by the world); bad
    env_kwargs raise ConfigError naming them."""
    import gymnasium

    try:
        return gymnasium.make(config.env, **config.env_kwargs)
    except (TypeError, ValueError, AssertionError, gymnasium.error.Error) as exc:
        why = str(exc).splitlines()[0] if str(exc) else "a bad value"
        raise ConfigError(f"[world] env_kwargs = {config.env_kwargs!r}: {config.env} refuses "
                          f"them ({type(exc).__name__}: {why})") from exc
