"""The world package's one root exception."""

from __future__ import annotations


class WorldError(Exception):
    """Root of every error raised by `world/` (bad configuration, unknown ids, bad snapshots)."""


class ConfigError(WorldError):
    """A `[world]` scenario table that cannot be turned into a city; names key, expected, actual."""


class CannotRecord(WorldError):
    """The world cannot write its own record of the run (trace.jsonl, health.jsonl) in the run
    folder, e.g. a full disk: it stops the run (world/process.py EXIT_CANNOT_WRITE) rather
    than run cycles that nothing records. The message names the file, the cycle and why."""
