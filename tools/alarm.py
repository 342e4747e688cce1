"""An alarm that interrupts a block of code after a time, for tools that must end a piece of
work that may not end by itself (`teleo solve --time-limit`, the fuzz drill's per-input
limit). Main thread only (SIGALRM)."""

from __future__ import annotations

import signal
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any


@contextmanager
def raised_after(seconds: float | None, error: Callable[[], BaseException]) -> Iterator[None]:
    """Raise ``error()`` in this thread when the block runs longer than ``seconds`` [s] (None
    or 0: never). Give a BaseException that is not an Exception, so that no handler of the
    code under the alarm takes it for a failure of its own."""
    if not seconds:
        yield
        return

    def ring(signum: int, frame: Any) -> None:
        raise error()

    previous = signal.signal(signal.SIGALRM, ring)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
