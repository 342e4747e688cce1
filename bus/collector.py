"""When a process collects its garbage: between cycles, off the lockstep's critical path."""

from __future__ import annotations

import gc


class Collector:
    """Garbage collection between cycles instead of inside them: the automatic collector is
    off while the stage runs (what start-up made is frozen out of every collection) and the
    young objects are collected right after a cycle's outputs are published, off the
    lockstep's critical path; an older generation every ``mid`` and ``full`` cycles.

    A cycle allocates in bursts (a decoded message is thousands of lists), and each burst
    would otherwise start collections in the middle of decoding or stepping."""

    def __init__(self, mid: int = 50, full: int = 1000) -> None:
        self.was_enabled = gc.isenabled()
        self.mid, self.full = mid, full
        self.cycles = 0
        gc.collect()
        gc.freeze()
        gc.disable()

    def after_cycle(self) -> None:
        self.cycles += 1
        gc.collect(2 if self.cycles % self.full == 0 else 1 if self.cycles % self.mid == 0 else 0)

    def close(self) -> None:
        gc.unfreeze()
        if self.was_enabled:
            gc.enable()
