"""When a process collects its garbage: between cycles, off the lockstep's critical path."""

from __future__ import annotations

import gc


class Collector:
    """Garbage collection between cycles instead of inside them: the automatic collector is
    off while the stage runs (what start-up made is frozen out of every collection) and the
    young objects are collected after every ``young``-th cycle's outputs are published, off the
    lockstep's critical path; an older generation every ``mid`` and ``full`` cycles (multiples
    of ``young``).

    A cycle allocates in bursts (a decoded message is thousands of lists), and each burst
    would otherwise start collections in the middle of decoding or stepping. Collecting the
    young objects only every tenth cycle skips what a cycle makes and the next ones drop
    again (indexes, belief sets), which makes a collection nearly ten times cheaper a cycle
    (docs/benchmarks.md, "Bus"); reference cycles then wait at most ten cycles to be freed."""

    def __init__(self, young: int = 10, mid: int = 50, full: int = 1000) -> None:
        if mid % young or full % mid:
            raise ValueError(f"Collector: mid ({mid}) must be a multiple of young ({young}) "
                             f"and full ({full}) of mid")
        self.was_enabled = gc.isenabled()
        self.young, self.mid, self.full = young, mid, full
        self.cycles = 0
        gc.collect()
        gc.freeze()
        gc.disable()

    def after_cycle(self) -> None:
        self.cycles += 1
        n = self.cycles
        if n % self.young == 0:
            gc.collect(2 if n % self.full == 0 else 1 if n % self.mid == 0 else 0)

    def close(self) -> None:
        gc.unfreeze()
        if self.was_enabled:
            gc.enable()
