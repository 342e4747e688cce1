"""Room on the run folder's file system: a launch stops its run in order while there is still
room for every file to be closed whole, rather than let the disk fill under it (docs/faults.md,
"A full disk").

A run writes about 1.7 kB a cycle (the demo: trace, snapshots, record), 300 kB a second at
full speed, in pieces of up to a few hundred kB (a record chunk, a checkpoint); what it writes
when it stops (the record's last chunk and index, the world's totals, the goal store) is a
few hundred kB more. So a run stops when less than RESERVE_BYTES are free, or less than
RESERVE_SHARE of a small file system (a 2 MB one: 512 kB).
"""

from __future__ import annotations

import os
from pathlib import Path

RESERVE_BYTES = 64 * 2**20  # [bytes] a run stops when less than this is free ...
RESERVE_SHARE = 0.25        # ... or less than this share of its file system's size


def room(path: Path) -> tuple[int, int] | None:
    """(free, total) [bytes] of the file system holding `path` (free: what this user may
    still write); None when it cannot tell."""
    try:
        st = os.statvfs(path)
    except OSError:
        return None
    return st.f_bavail * st.f_frsize, st.f_blocks * st.f_frsize


def reserve(total: int) -> int:
    """[bytes] that must stay free on a file system of `total` bytes (module doc)."""
    return min(RESERVE_BYTES, int(total * RESERVE_SHARE))


def size_text(n: int) -> str:
    """A byte count for a person: 512 B, 40.0 kB, 1.5 MB, 3.2 GB."""
    for unit, scale in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= scale:
            return f"{n / scale:.1f} {unit}"
    return f"{n} B"


def shortage(path: Path) -> str:
    """"" while the file system of `path` has its reserve free; else the end of a sentence
    about it: "is nearly full (... free of ...; ...)"."""
    got = room(path)
    if got is None:
        return ""
    free, total = got
    need = reserve(total)
    if free >= need:
        return ""
    return (f"is nearly full ({size_text(free)} free of {size_text(total)}; "
            f"a run keeps {size_text(need)} free to close its files whole)")


def free_text(path: Path) -> str:
    """"2.0 kB free of 2.1 MB" for the file system of `path` ("" when it cannot tell)."""
    got = room(path)
    return "" if got is None else f"{size_text(got[0])} free of {size_text(got[1])}"
