"""How busy the machine is, so that waits for processes to start or answer follow what the
machine is doing rather than a fixed figure: on a heavily loaded machine a fixed start limit fails
launches where nothing is wrong but the load.

``busy()`` is the 1-minute load average per CPU this process may use, at least 1 (an idle or
lightly loaded machine: the figures as written); ``scaled(seconds)`` stretches a limit by it,
up to ``MOST`` times; ``overloaded(waited)`` is the clause a message of a wait that ran out
adds to say that the machine was overloaded (empty when it was not)."""

from __future__ import annotations

import os

MOST = 8.0  # a limit is never stretched beyond this many times its figure


def now() -> tuple[float, int]:
    """(the 1-minute load average, the CPUs this process may use); (0.0, 1) when unknown."""
    try:
        return os.getloadavg()[0], len(os.sched_getaffinity(0))
    except (OSError, AttributeError):
        return 0.0, 1


def busy(load: tuple[float, int] | None = None) -> float:
    """The load average per usable CPU, at least 1.0; `load`: (average, CPUs), else now."""
    average, cpus = load or now()
    return max(1.0, average / max(1, cpus))


def scaled(seconds: float, most: float = MOST, load: tuple[float, int] | None = None
           ) -> float:
    """`seconds` [s] stretched by how busy the machine is (``busy``), at most `most` times."""
    return seconds * min(most, busy(load))


def overloaded(waited: float, load: tuple[float, int] | None = None) -> str:
    """"" on a machine that is not busy (under 1.5 runnable processes per CPU); else
    "; the machine is overloaded (...)", for the one line of a wait that ran out after
    `waited` [s]."""
    average, cpus = load or now()
    if busy((average, cpus)) < 1.5:
        return ""
    return (f"; the machine is overloaded (load average {average:.1f} on {cpus} CPU(s)): "
            f"waited {waited:.0f} s, the limit stretched by the load; try again when it is "
            f"less busy")
