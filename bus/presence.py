"""Who is up: liveliness tokens teleo/<run>/proc/<process>, tracked by a liveliness
subscriber (history on) and seeded by one liveliness get.

Liveliness shows presence, not progress: a SIGKILLed process vanishes within milliseconds,
a SIGSTOPped one only when its lease expires, a hung one never (docs/bus.md, "Zenoh in Python",
item 3). The clock's per-cycle deadline covers the latter two.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

import zenoh

from bus import keys


class Presence:
    """Thread-safe set of live process names, with a per-name incarnation counter
    (incremented at each appearance) so a quick restart is still noticed."""

    def __init__(self, session: zenoh.Session, run: str, sync_timeout: float = 1.0) -> None:
        self.run = run
        self._cond = threading.Condition()
        self._alive: set[str] = set()
        self._seen: set[str] = set()
        self._incarnation: dict[str, int] = {}
        liveliness = session.liveliness()
        self._sub = liveliness.declare_subscriber(
            keys.all_procs(run), self._on_sample, history=True)
        for reply in liveliness.get(keys.all_procs(run), timeout=sync_timeout):
            if reply.ok is not None:
                self._apply(str(reply.ok.key_expr), alive=True, only_unseen=True)

    def _on_sample(self, sample: zenoh.Sample) -> None:
        self._apply(str(sample.key_expr), alive=sample.kind == zenoh.SampleKind.PUT)

    def _apply(self, key: str, alive: bool, only_unseen: bool = False) -> None:
        name = keys.process_of_token(self.run, key)
        if name is None:
            return
        with self._cond:
            if only_unseen and name in self._seen:
                return
            self._seen.add(name)
            if alive and name not in self._alive:
                self._alive.add(name)
                self._incarnation[name] = self._incarnation.get(name, 0) + 1
            elif not alive:
                self._alive.discard(name)
            self._cond.notify_all()

    def snapshot(self) -> frozenset[str]:
        with self._cond:
            return frozenset(self._alive)

    def incarnations(self) -> dict[str, int]:
        """How many times each process has appeared so far."""
        with self._cond:
            return dict(self._incarnation)

    def wait_for(self, predicate: Callable[[frozenset[str]], bool], timeout: float) -> bool:
        """Wait up to `timeout` [s] until `predicate(live names)` holds; return whether it did."""
        deadline = time.monotonic() + timeout
        with self._cond:
            while not predicate(frozenset(self._alive)):
                remaining = deadline - time.monotonic()
                if remaining <= 0:
                    return False
                self._cond.wait(remaining)
            return True

    def wait_change(self, timeout: float) -> None:
        """Block until any token appears or disappears, or `timeout` [s] passes."""
        with self._cond:
            self._cond.wait(timeout)
