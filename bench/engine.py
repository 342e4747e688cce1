"""Benchmark: one engine cycle (inference + decision) against the number of objects.

Blocks World (programs/blocks.tlp: joins on shared attributes, numeric tests, negation,
recursion) with N blocks in towers of height 1..4 on one table. Prints ms per cycle (median).
The rows 10, 100, 1000 infer from scratch every cycle (the memo is dropped before each call);
"1000 same" repeats one world (equal percepts in new lists each cycle, so every stratum is
reused); "1000 1%" moves ~1% of the blocks each cycle (top blocks onto new towers).
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


def drift(n: int, cycles: int, seed: int = 1) -> list[list[list]]:
    """``cycles`` successive worlds of N blocks, each moving max(1, N/100) top blocks onto
    new single-block towers to the right (a legal Blocks World move)."""
    rnd = random.Random(seed)
    ps = world(n)
    out = [ps]
    for _ in range(cycles - 1):
        ps = [list(p) for p in ps]
        right = max(p[3] for p in ps if p[0] == "block") + 3
        for _ in range(max(1, n // 100)):
            tops = _tops(ps)
            b = ps[rnd.choice(tops)]
            b[3], b[5] = right, 2
            right += 3
        out.append(ps)
    return out


def _tops(ps: list[list]) -> list[int]:
    """Indexes of blocks with nothing on them."""
    top: dict[int, tuple[int, int]] = {}
    for i, p in enumerate(ps):
        if p[0] == "block" and (p[3] not in top or p[5] > top[p[3]][1]):
            top[p[3]] = (i, p[5])
    return [i for i, _ in top.values()]


def timed(fn, repeat: int) -> float:
    """Median wall time of fn() [ms]."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append((time.perf_counter() - t0) * 1000)
    return statistics.median(times)


def goal_state(engine: Engine, n: int):
    """Clear the bottom block of the first tower, and stack the last block on B0."""
    state = engine.add_goal(engine.initial_state(), f"(on B{n - 1} B0)")
    state = engine.remove_goal(state, "p1")
    return engine.add_goal(state, "(clear B0)", priority=0)


def row(engine: Engine, label: str, worlds: list[list[list]], repeat: int, keep: bool) -> None:
    """Time infer, decide and cycle over ``worlds`` in turn (one per call, cycling round);
    ``keep``: keep the inference memo between calls (else every call starts from scratch)."""
    n = sum(1 for p in worlds[0] if p[0] == "block")
    state = goal_state(engine, n)
    objs = [as_percepts(w) for w in worlds]
    beliefs = [engine.infer(o) for o in objs]
    step = iter(range(10**9))

    def pick() -> int:
        if not keep:
            engine.inference.forget()
        return next(step) % len(objs)

    t_infer = timed(lambda: engine.infer(PerceptIndex(objs[pick()])), repeat)
    t_decide = timed(lambda: engine.decide(state, PerceptIndex(objs[i := pick()]), beliefs[i]),
                     repeat)
    t_cycle = timed(lambda: engine.cycle(state, objs[pick()]), repeat)
    print(f"{label:>8} {len(worlds[0]):>9} {len(beliefs[0]):>8} {t_infer:>9.3f} "
          f"{t_decide:>10.3f} {t_cycle:>9.3f}")


def main() -> None:
    program = load_program(ROOT / "programs" / "blocks.tlp")
    print(f"{'objects':>8} {'percepts':>9} {'beliefs':>8} {'infer ms':>9} {'decide ms':>10} "
          f"{'cycle ms':>9}")
    for n in (10, 100, 1000):
        repeat = 200 if n <= 100 else 30
        row(Engine(program), str(n), [world(n)], repeat, keep=False)
    row(Engine(program), "1000 same", [copy(world(1000)) for _ in range(2)], 30, keep=True)
    row(Engine(program), "1000 1%", drift(1000, 31), 30, keep=True)


def copy(ps: list[list]) -> list[list]:
    """Equal percepts in new lists (as they arrive from the bus each cycle)."""
    return [list(p) for p in ps]


if __name__ == "__main__":
    main()
