"""How `teleo launch` takes a stop signal, from its first instant to its exit (docs/faults.md,
"Signals").

SIGINT, SIGTERM and SIGHUP each ask a launch to stop its run in order. They are handled in
three phases, so that none is lost and none cuts the stop short:

- **starting the command** (importing its modules, seconds on a busy machine): `early()`,
  which the `teleo` command calls before it imports anything else when the command is
  `launch`, only notes the signal. Without it a SIGINT that the shell had set to be ignored
  (a non-interactive shell does so for its background jobs) was dropped by the kernel until
  the launcher set its own handler, and the run went on;
- **starting and running the run**: `running()` makes each signal raise KeyboardInterrupt
  at once (one noted earlier included), which ends the start-up or the run in order;
- **stopping**: `stopping(hook)` raises nothing, so a second signal (Ctrl-C pressed again, a
  `teleo stop` after a Ctrl-C) never breaks off the stop, the registry entry, the record or
  the summary; it calls `hook` instead (the launcher then stops waiting for its record's last
  messages, and the summary says which cycles the record lacks).

SIGINT is taken even when it was inherited ignored. POSIX has a non-interactive shell start
its background jobs with SIGINT ignored so that a Ctrl-C meant for the script does not kill
them; a launcher is the supervisor of a run, and a SIGINT sent to it (`kill -INT`, or that
Ctrl-C) is a request to stop that run, which it does in order and with a summary, rather
than leaving a run going that nothing will stop. Every other `teleo` command keeps the
disposition it was given. SIGTERM always works, whatever the shell did.
"""

from __future__ import annotations

import signal
import sys
from collections.abc import Callable, Sequence

STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)
_noted: list[int] = []  # signals that came while the command was starting


def _note(signum: int, frame: object) -> None:
    _noted.append(signum)


def _raise(signum: int, frame: object) -> None:
    raise KeyboardInterrupt


def command_of(argv: Sequence[str]) -> str:
    """The subcommand of a `teleo` command line (the first argument that is not an option:
    the group's own options, -v, -h and --version, take no value)."""
    return next((a for a in argv if not a.startswith("-")), "")


def early(argv: Sequence[str] | None = None) -> bool:
    """For `teleo launch` only: note every stop signal from now on (see the module doc);
    returns whether it did. Call it before importing anything slow."""
    if command_of(sys.argv[1:] if argv is None else argv) != "launch":
        return False
    for sig in STOP_SIGNALS:
        signal.signal(sig, _note)
    return True


def noted() -> tuple[int, ...]:
    """The stop signals noted while the command started."""
    return tuple(_noted)


def running() -> None:
    """From now on a stop signal raises KeyboardInterrupt; raises it at once when one came
    while the command was starting (the handler is set first, so none falls between)."""
    for sig in STOP_SIGNALS:
        signal.signal(sig, _raise)
    if _noted:
        raise KeyboardInterrupt


def stopping(hook: Callable[[], None] | None = None) -> None:
    """From now on a stop signal calls `hook` (which must only set a flag or an Event: it
    runs between two bytecodes of whatever the main thread does) and raises nothing."""

    def again(signum: int, frame: object) -> None:
        if hook is not None:
            hook()

    for sig in STOP_SIGNALS:
        signal.signal(sig, again)
