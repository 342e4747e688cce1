"""A world's static configuration, sent once per run rather than in every snapshot.

The keys of a snapshot that stay the same for a whole run are its Domain's ``static_keys``
(world/domain.py: driving's and the office's "config", the blocks table): the world process
sends them once (docs/bus.md, "world/static") and each world state without them; a reader
puts the two back together before it hands the snapshot to the world's own code (perceive,
render, plot), which always sees a whole snapshot. `teleo simulate` takes the same path in
one process, and a run record holds the static part once (tools/records/run_record.py).

split   (static part, moving part) of a whole snapshot dict; the moving part keeps "domain"
whole   a snapshot dict with its static part put back (as it is if it has it already)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from world.domain import domain_of
from world.errors import ConfigError, WorldError


def static_keys(snapshot: Mapping[str, Any]) -> tuple[str, ...]:
    """The static keys of a snapshot's domain (none for a domain not installed here)."""
    try:
        return domain_of(snapshot).static_keys  # type: ignore[arg-type]
    except ConfigError:
        return ()


def split(snapshot: Mapping[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """(static part, moving part) of a snapshot dict."""
    names = static_keys(snapshot)
    return ({k: snapshot[k] for k in names if k in snapshot},
            {k: v for k, v in snapshot.items() if k not in names})


def has_static(snapshot: Mapping[str, Any]) -> bool:
    """Whether a snapshot is whole: its domain has no static keys, or it holds some (a world
    state as sent holds none of them)."""
    names = static_keys(snapshot)
    return not names or any(k in snapshot for k in names)


def whole(static: Mapping[str, Any] | None, snapshot: dict[str, Any]) -> dict[str, Any]:
    """``snapshot`` with the static part put back; one that holds it already is returned as
    it is. Raises WorldError naming the missing keys when it lacks them and ``static`` does
    not give them (the run's static part never reached this reader)."""
    names = static_keys(snapshot)
    if not names or any(k in snapshot for k in names):   # has_static, its keys looked up once
        return snapshot
    merged = {**(static or {}), **snapshot}
    missing = [k for k in names if k not in merged]
    if len(missing) == len(names):
        raise WorldError(f"world state of cycle {snapshot.get('cycle', '?')}: no static "
                         f"{', '.join(missing)} (the run's world/static was not received)")
    return merged
