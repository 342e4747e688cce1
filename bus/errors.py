"""Errors of the bus layer: one root, each naming the object, what was expected and where."""

from __future__ import annotations


class BusError(Exception):
    """Root of every error raised by `bus`."""


class KeyFormatError(BusError, ValueError):
    """A name used as one key chunk (run, agent, process) is not a plain chunk."""


class CodecError(BusError):
    """A payload could not be encoded or decoded; the message names the key and the problem."""

    def __init__(self, key: str, problem: str) -> None:
        super().__init__(f"{key}: {problem}")
        self.key = key
        self.problem = problem


class Refused(BusError):
    """A stage's step refuses the inputs of a cycle: a message its reader finds malformed (a
    world state whose snapshot is not its world's, percepts the engine cannot read). The
    stage logs the reason, publishes nothing and leaves the cycle undone, so the next copy
    of it (the world re-sends a waiting state every second) is handled as new; the process
    goes on (docs/faults.md, "Hostile input")."""


class ConfigError(BusError, ValueError):
    """A bus configuration value (mode, endpoint, env var) is invalid."""


class NobodyServing(BusError):
    """A query got no reply: no process serves that key (or none answered in time)."""

    def __init__(self, key: str, timeout: float) -> None:
        super().__init__(
            f"nobody is serving {key!r}: no queryable answered within {timeout:g} s "
            "(is the process that serves it running and on the same bus?)"
        )
        self.key = key
        self.timeout = timeout


class QueryFailed(BusError):
    """The serving process answered a query with an error reply."""

    def __init__(self, key: str, reason: str) -> None:
        super().__init__(f"query {key!r} failed on the serving side: {reason}")
        self.key = key
        self.reason = reason


class NotReady(BusError):
    """The start-up barrier timed out; names the processes that never announced themselves."""

    def __init__(self, missing: set[str], timeout: float, detail: str = "") -> None:
        names = ", ".join(sorted(missing)) or "(none)"
        extra = f"; {detail}" if detail else ""
        super().__init__(f"not ready after {timeout:g} s: missing processes {names}{extra}")
        self.missing = frozenset(missing)
        self.timeout = timeout


class ClockStopped(BusError):
    """Policy "stop": a stage stayed dead past the restart timeout, so the clock stops."""

    def __init__(self, cycle: int, dead: tuple[str, ...], report: object) -> None:
        super().__init__(
            f"clock stopped at cycle {cycle}: stage(s) {', '.join(dead)} gone and not back "
            "within the restart timeout"
        )
        self.cycle = cycle
        self.dead = dead
        self.report = report


class PaceLost(BusError):
    """A lockstep run's recorder, which the world keeps pace with, left the bus or stopped
    moving and was not back within its limit: the world stops rather than run cycles that
    nothing records (bus/clock.py Clock.keep_pace)."""


class RouterError(BusError):
    """The router subprocess did not start or did not report its endpoint."""
