"""Benchmark: what one engine cycle costs, from percept lists as the bus delivers them to the
decision, against the previous release's engine on the same inputs in the same process.

Workload (issue 13): N blocks in towers of 1..4 on one table, each block with a color and a
distance [m]; tests/lang/fixtures/blocks_handwritten.tlp (programs/blocks.tlp as it was before
the problem solver learned its skills: both engines run the same hand-written skills, ours with
``solver=None`` as the baseline has none), bench/speed/towers.tlp and bench/speed/samecolor.tlp
(joins on shared attributes, numeric tests, negation, recursion, ``near`` reading the distance,
``samecolor`` joined by a shared variable; ``--without-samecolor`` leaves it out, which the
previous release evaluated in quadratic time). Every cycle's percepts are new lists decoded by
msgpack, as from the bus. Rows:

  all     every block's distance changes (the geometry stays put)
  1%      max(1, N/100) blocks' distances change
  none    nothing changes (equal values in new lists)
  move    max(1, N/100) top blocks move onto new towers (the geometry changes)
  scratch every call starts from scratch (``inference.forget()`` first)

"infer" times ``Engine.infer(lists)``; "bus" times what the inference process pays for a
message as it arrives: ``bus.codec.decode`` of the Percepts payload (each row packed on its own;
a row whose bytes were in the last message comes back as the same list) and ``infer`` of those
rows as ``SharedRows`` (ours; the baseline gets the same decoded tuple), collecting garbage
after each call as a stage process does (bus/collector.py, untimed); "cycle" times
``Engine.cycle(state, lists)`` (infer and the executive's decision). Each figure is the median
over the cycles of a row [ms], of this thread's CPU time by default (``--clock wall`` for wall
time); "x" is the baseline's median over ours; "gc" counts the garbage collections that
started during the timed infer calls, per call. "diff" is a second baseline, the least a
Python program does to learn what changed, with no inference at all: the same lists as tuples
in a set, diffed with last cycle's set both ways; "x diff" is its median over infer's. Its
growth from one size to the next, printed after the table beside infer's, is what this machine
charges plain Python for more objects (a working set outgrowing the caches costs more per
object), against which the engine's growth is read.
The baseline is commit a24e6ef's agents/lang (git archive, imported as another package), run
with its cross-cycle reuse as it shipped; at 10,000 objects it is timed on one call per column
(its quadratic ``samecolor`` makes a call last half a minute), and only the issue's rows run.
Run: .venv/bin/python bench/speed/engine.py [--sizes 10,100,1000,10000] [--gc on|off|freeze]
"""

from __future__ import annotations

import argparse
import gc
import importlib.util
import io
import random
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from itertools import pairwise
from pathlib import Path

import msgpack

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from agents.lang import Engine, SharedRows, load_program  # noqa: E402
from bus import keys  # noqa: E402
from bus.codec import decode, encode  # noqa: E402
from bus.collector import Collector  # noqa: E402
from bus.messages import Envelope, Percepts  # noqa: E402

BASELINE = "a24e6ef"
PROGRAM = (ROOT / "tests" / "lang" / "fixtures" / "blocks_handwritten.tlp",
           ROOT / "bench" / "speed" / "towers.tlp", ROOT / "bench" / "speed" / "samecolor.tlp")
COLORS = ("red", "green", "blue")
KINDS = ("all", "1%", "none", "move", "scratch")


def load_baseline(tmp: Path):
    """The previous release's agents/lang, imported as package ``baseline_lang``."""
    tar = subprocess.run(["git", "archive", BASELINE, "agents/lang"], cwd=ROOT, check=True,
                         capture_output=True).stdout
    with tarfile.open(fileobj=io.BytesIO(tar)) as t:
        t.extractall(tmp, filter="data")
    pkg = tmp / "agents" / "lang"
    spec = importlib.util.spec_from_file_location("baseline_lang", pkg / "__init__.py",
                                                  submodule_search_locations=[str(pkg)])
    mod = importlib.util.module_from_spec(spec)
    sys.modules["baseline_lang"] = mod
    spec.loader.exec_module(mod)
    return mod


def world(n: int, rnd: random.Random) -> list[list]:
    """Table, hand and N blocks B0..B(n-1) in random towers, as neutral lists."""
    out = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"]]
    i, x = 0, 0
    while i < n:
        for level in range(min(rnd.randint(1, 4), n - i)):
            out.append(["block", f"B{i}", "xpos", x, "ypos", 2 + 2 * level, "height", 2,
                        "color", rnd.choice(COLORS),
                        "distance", round(rnd.uniform(0, 20), 3) + 0.0005])
            i += 1
        x += 3
    return out


def cycles(n: int, kind: str, count: int, seed: int = 1) -> list[bytes]:
    """``count`` successive cycles' percepts, msgpack-encoded as on the bus (decoded one by one
    just before each call, so that every cycle brings new objects and the process holds one
    message at a time)."""
    rnd = random.Random(seed)
    ps = world(n, random.Random(0))
    blocks = [p for p in ps if p[0] == "block"]
    k = max(1, n // 100)
    out = []
    for _ in range(count):
        out.append(msgpack.packb(ps))
        if kind in ("all", "1%"):
            for b in (blocks if kind == "all" else rnd.sample(blocks, min(k, len(blocks)))):
                b[11] = round(max(0.0, b[11] + rnd.uniform(-0.5, 0.5)), 3) + 0.0005
        elif kind == "move":
            right = max(b[3] for b in blocks) + 3
            for _ in range(k):
                b = _top(blocks, rnd)
                b[3], b[5] = right, 2
                right += 3
    return out


def as_messages(seq: list[bytes], agent: str) -> list[bytes]:
    """The same cycles as Percepts payloads from ``agent``'s perception (fresh lists each
    cycle, as a perception process makes them)."""
    return [encode(Percepts(Envelope(1, "bench", t, f"{agent}.perception", 0), agent,
                            tuple(msgpack.unpackb(raw)))) for t, raw in enumerate(seq)]


def _top(blocks: list[list], rnd: random.Random) -> list:
    """A block with nothing on it."""
    top: dict[int, list] = {}
    for b in blocks:
        if b[3] not in top or b[5] > top[b[3]][5]:
            top[b[3]] = b
    return rnd.choice(sorted(top.values(), key=lambda b: b[1]))


def goal_state(engine, n: int):
    """Clear the bottom block of the first tower, and stack the last block on B0."""
    state = engine.add_goal(engine.initial_state(), f"(on B{n - 1} B0)")
    state = engine.remove_goal(state, "p1")
    return engine.add_goal(state, "(clear B0)", priority=0)


def measure(engine, kind: str, seq: list[bytes], calls: int, clock, freeze: bool,
            shared: bool, tag: str) -> tuple:
    """Median infer, bus and cycle time [ms] over the cycles of ``seq`` in turn, the beliefs
    and the collections per infer; ``freeze``: ``gc.freeze()`` after the first two cycles;
    ``shared``: the engine gets the decoded rows as SharedRows; ``tag``: a key of its own."""
    first = msgpack.unpackb(seq[0])
    state = goal_state(engine, sum(1 for p in first if p[0] == "block"))
    beliefs = len(engine.infer(first))
    engine.cycle(state, msgpack.unpackb(seq[1]))
    key = keys.percepts("bench", tag)
    msgs = as_messages(seq, tag)
    wrap = SharedRows if shared else tuple
    if freeze:
        gc.collect()
        gc.freeze()
    times: dict[str, list[float]] = {"infer": [], "bus": [], "cycle": []}
    collections = [0, False]  # garbage collections started during timed infer calls

    def count(phase: str, info: dict) -> None:
        collections[0] += phase == "start" and collections[1]

    gc.callbacks.append(count)
    step = 2
    for what in ("infer", "bus", "cycle"):
        if what == "bus":
            engine.inference.forget()  # the bus rows are other lists than the infer row's
            engine.infer(wrap(decode(key, msgs[(step - 1) % len(seq)]).percepts))  # untimed
            collector = Collector()  # as a stage process collects: after each cycle
        for _ in range(calls):
            i = step % len(seq)
            step += 1
            if kind == "scratch":
                engine.inference.forget()
            if what == "bus":
                payload = msgs[i]
                t0 = clock()
                engine.infer(wrap(decode(key, payload).percepts))
                times[what].append((clock() - t0) * 1000)
                collector.after_cycle()
                continue
            ps = msgpack.unpackb(seq[i])
            collections[1] = what == "infer"
            t0 = clock()
            if what == "infer":
                engine.infer(ps)
            else:
                engine.cycle(state, ps)
            times[what].append((clock() - t0) * 1000)
            collections[1] = False
        if what == "bus":
            collector.close()
    gc.callbacks.remove(count)
    gc.unfreeze()
    return (*(statistics.median(times[w]) for w in ("infer", "bus", "cycle")), beliefs,
            collections[0] / calls)


def diff_baseline(seq: list[bytes], calls: int, clock) -> float:
    """Median time [ms] of the plain-Python change detection over the cycles of ``seq``:
    every row as a tuple in a set, diffed with the last cycle's set both ways."""
    last = set(map(tuple, msgpack.unpackb(seq[0])))
    times = []
    for step in range(1, calls + 1):
        rows = msgpack.unpackb(seq[step % len(seq)])
        t0 = clock()
        now = set(map(tuple, rows))
        added, gone = now - last, last - now
        last = now
        times.append((clock() - t0) * 1000)
    del added, gone
    return statistics.median(times)


def growth(results: dict) -> None:
    """Each kind's cost growth from one size to the next: infer's against plain Python's."""
    for kind in KINDS:
        sizes = sorted(n for (n, k) in results if k == kind)
        for a, b in pairwise(sizes):
            (ia, _, da), (ib, _, db) = results[(a, kind)], results[(b, kind)]
            print(f"growth {kind:>7} {a} -> {b} objects ({b / a:g}x): infer {ib / ia:.1f}x, "
                  f"plain-Python diff {db / da:.1f}x")


def _sizes(text: str) -> list[int]:
    """Positive object counts, comma-separated."""
    parts = text.split(",")
    if not all(p.isdigit() and int(p) > 0 for p in parts):
        raise argparse.ArgumentTypeError(f"expected positive counts like 100,1000, got {text!r}")
    return [int(p) for p in parts]


def _kinds(text: str) -> list[str]:
    """Row kinds, comma-separated, each one of KINDS."""
    parts = text.split(",")
    bad = [p for p in parts if p not in KINDS]
    if bad:
        raise argparse.ArgumentTypeError(f"unknown row {bad[0]!r}; known: {', '.join(KINDS)}")
    return parts


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", default="10,100,1000,10000", type=_sizes,
                    help="object counts, comma-separated")
    ap.add_argument("--kinds", default=",".join(KINDS), type=_kinds,
                    help=f"rows, comma-separated: {', '.join(KINDS)}".replace("%", "%%"))
    ap.add_argument("--gc", choices=("on", "off", "freeze"), default="on",
                    help="garbage collector during the runs (freeze: gc.freeze() after the "
                         "first two cycles)")
    ap.add_argument("--without-samecolor", action="store_true",
                    help="leave bench/speed/samecolor.tlp out of the program")
    ap.add_argument("--clock", choices=("cpu", "wall"), default="cpu",
                    help="cpu: this thread's CPU time (steadier on a shared machine); wall")
    args = ap.parse_args()
    clock = time.thread_time if args.clock == "cpu" else time.perf_counter
    with tempfile.TemporaryDirectory() as tmp:
        base = load_baseline(Path(tmp))
        files = PROGRAM[:2] if args.without_samecolor else PROGRAM
        ours_prog, base_prog = load_program(*files), base.load_program(*files)
        if args.gc == "off":
            gc.disable()
        print(f"{'objects':>8} {'change':>7} {'beliefs':>7} | {'infer':>7} {'base':>7} {'x':>6} |"
              f" {'bus':>7} {'base':>7} {'x':>6} | {'cycle':>7} {'base':>7} {'x':>6} |"
              f" {'gc':>4} {'base':>4}   [ms {args.clock} time, median; gc: collections per infer]")
        results = {}
        for n in args.sizes:
            calls = 40 if n <= 100 else 20 if n <= 1000 else 3
            for kind in args.kinds:
                if n > 1000 and kind in ("move", "scratch") and args.kinds == list(KINDS):
                    continue  # by default the largest size has the three rows only
                seq = cycles(n, kind, 2 * calls + 2)
                row = []
                for make, k, ours in (
                        (lambda: Engine(ours_prog, solver=None), calls, True),
                        (lambda: base.Engine(base_prog), calls if n <= 1000 else 1, False)):
                    engine = make()  # (the baseline takes half a minute a call at 10,000)
                    row.append(measure(engine, kind, seq, k, clock, args.gc == "freeze", ours,
                                       f"{'ours' if ours else 'base'}-{n}-{kind}"))
                    del engine
                (i, u, c, b, g), (bi, bu, bc, _, bg) = row
                d = diff_baseline(seq, calls, clock)
                results[(n, kind)] = (i, u, d)
                print(f"{n:>8} {kind:>7} {b:>7} | {i:>7.3f} {bi:>7.3f} {bi / i:>5.1f}x |"
                      f" {u:>7.3f} {bu:>7.3f} {bu / u:>5.1f}x |"
                      f" {c:>7.3f} {bc:>7.3f} {bc / c:>5.1f}x | {d:>7.3f} {d / i:>5.2f}x |"
                      f" {g:>4.2f} {bg:>4.2f}", flush=True)
                del seq
        growth(results)
        targets(results)


def targets(results: dict) -> None:
    """The issue's targets for a whole infer, met or not on this machine."""
    for (n, kind), limit in (((1000, "all"), 2.0), ((100, "all"), 0.25), ((1000, "none"), 0.3)):
        got = results.get((n, kind))
        if got is not None:
            for name, ms in zip(("from lists", "from bytes (bus)"), got[:2], strict=True):
                verdict = "met" if ms <= limit else "NOT met"
                print(f"target: infer at {n} objects, {kind:>4} changed <= {limit} ms, "
                      f"{name}: {ms:.3f} ms, {verdict}")


if __name__ == "__main__":
    main()
