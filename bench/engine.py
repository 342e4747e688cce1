"""Benchmark: one engine cycle (inference + decision) against the number of objects.

Blocks World (programs/blocks.tlp: joins on shared attributes, numeric tests, negation,
recursion) with N blocks in towers of height 1..4 on one table. Prints ms per cycle (median).
Run: .venv/bin/python bench/engine.py
"""

from __future__ import annotations

import random
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from agents.lang import Engine, load_program  # noqa: E402
from agents.lang.engine import as_percepts  # noqa: E402
from agents.lang.store import PerceptIndex  # noqa: E402


def world(n: int, seed: int = 0) -> list[list]:
    """N blocks B0..B(n-1) in random towers, as neutral percepts."""
    rnd = random.Random(seed)
    out = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"]]
    i, x = 0, 0
    while i < n:
        for level in range(min(rnd.randint(1, 4), n - i)):
            out.append(["block", f"B{i}", "xpos", x, "ypos", 2 + 2 * level, "height", 2])
            i += 1
        x += 3
    return out


def timed(fn, repeat: int) -> float:
    """Median wall time of fn() [ms]."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) * 1000)
    return statistics.median(times)


def main() -> None:
    engine = Engine(load_program(ROOT / "programs" / "blocks.tlp"))
    print(f"{'objects':>8} {'percepts':>9} {'beliefs':>8} {'infer ms':>9} {'decide ms':>10} "
          f"{'cycle ms':>9}")
    for n in (10, 100, 1000):
        percepts = world(n)
        # the goal: clear the bottom block of the first tower, and stack the last block on B0
        state = engine.add_goal(engine.initial_state(), f"(on B{n - 1} B0)")
        state = engine.remove_goal(state, "p1")
        state = engine.add_goal(state, "(clear B0)", priority=0)
        objs = as_percepts(percepts)
        repeat = 200 if n <= 100 else 30
        beliefs = engine.infer(objs)
        t_infer = timed(lambda objs=objs: engine.infer(PerceptIndex(objs)), repeat)
        t_decide = timed(lambda objs=objs, s=state, b=beliefs:
                         engine.decide(s, PerceptIndex(objs), b), repeat)
        t_cycle = timed(lambda objs=objs, s=state: engine.cycle(s, objs), repeat)
        print(f"{n:>8} {len(percepts):>9} {len(beliefs):>8} {t_infer:>9.3f} {t_decide:>10.3f} "
              f"{t_cycle:>9.3f}")


if __name__ == "__main__":
    main()
