"""What a run record holds and what it lacks, as a launch's summary tells it: the ranges of
cycles whose world state it lacks (docs/faults.md: a router kill can cost the
record many of a run's cycles, and the summary says which)."""

from __future__ import annotations

import logging
from pathlib import Path
from typing import Any

from tools.records.run_record import RECORD_FILE, RecordError, RunRecord

log = logging.getLogger(__name__)


def missing_ranges(held: list[list[int]], cycles: int) -> list[list[int]]:
    """The ranges of 0..cycles-1 that `held` (cycle_ranges) does not cover."""
    out, nxt = [], 0
    for first, last in held:
        if first > nxt and nxt < cycles:
            out.append([nxt, min(first, cycles) - 1])
        nxt = max(nxt, last + 1)
    if nxt < cycles:
        out.append([nxt, cycles - 1])
    return out


def coverage(run_dir: Path, cycles: int, record: RunRecord | None = None
             ) -> dict[str, Any] | None:
    """How much of a run of `cycles` cycles its record holds: {"file", "world_states",
    "missing" (how many cycles' world states it lacks), "gaps" ([[first, last], ...] of
    those cycles)}; "missing" and "gaps" are None when the record cannot be read at all;
    None when there is no record."""
    path = Path(run_dir) / RECORD_FILE
    if not path.is_file():
        return None
    try:
        record = record if record is not None else RunRecord(path)
        held = record.held_ranges()
    except RecordError as exc:
        log.warning("record not read: %s", exc)
        return {"file": str(path), "world_states": None, "missing": None, "gaps": None}
    gaps = missing_ranges(held, cycles)
    return {"file": str(path), "world_states": sum(b - a + 1 for a, b in held),
            "missing": sum(b - a + 1 for a, b in gaps), "gaps": gaps}


def ranges_text(ranges: list[list[int]], most: int = 6) -> str:
    """"5-9, 40, 100-199": cycle ranges for a person (the first `most`, then a count)."""
    parts = [f"{a}-{b}" if b > a else f"{a}" for a, b in ranges]
    if len(parts) > most:
        parts = parts[:most] + [f"... {len(parts) - most} more"]
    return ", ".join(parts)
