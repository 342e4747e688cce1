"""How busy the machine is, so that waits for processes to start or answer follow what the
machine is doing rather than a fixed figure (issue 31: at a 1-minute load average of 20-46 on
2 CPUs, launches failed at the router's 15 s start limit and tools passed 30 s, while nothing
was wrong but the load).

``busy()`` is the 1-minute load average per CPU this process may use, at least 1 (an idle or
lightly loaded machine: the figures as written); ``scaled(seconds)`` stretches a limit by it,
up to ``MOST`` times. A limit that is scaled says so when it is reached (``overloaded``)."""

from __future__ import annotations

import os

MOST = 8.0  # a limit is never stretched beyond this many times its figure


def busy() -> float:
    """The 1-minute load average per usable CPU, at least 1.0 (1.0 when it cannot be read)."""
    try:
        load = os.getloadavg()[0]
        cpus = len(os.sched_getaffinity(0))
    except (OSError, AttributeError):
        return 1.0
    return max(1.0, load / max(1, cpus))


def scaled(seconds: float, most: float = MOST) -> float:
    """`seconds` [s] stretched by how busy the machine is now (``busy``), at most `most`
    times."""
    return seconds * min(most, busy())


def overloaded(waited: float) -> str:
    """"" on a machine that is not busy; else a clause saying that it is, for the one-line
    message of a wait that ran out after `waited` [s]."""
    factor = busy()
    if factor <= 1.5:
        return ""
    try:
        load = os.getloadavg()[0]
    except OSError:
        return ""
    return (f"; the machine is overloaded (load average {load:.1f} on "
            f"{len(os.sched_getaffinity(0))} CPU(s)), so it waited {waited:.0f} s")
