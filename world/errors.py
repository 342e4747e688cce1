"""The world package's one root exception."""

from __future__ import annotations


class WorldError(Exception):
    """Root of every error raised by `world/` (bad configuration, unknown ids, bad snapshots)."""


class ConfigError(WorldError):
    """A `[world]` scenario table that cannot be turned into a city; names key, expected, actual."""
