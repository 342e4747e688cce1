"""Benchmark: teleo's means-ends problem solving and skill learning (seed 000, "Problem Solving
and Skill Learning") on random Blocks World problems nobody picked, against pyperplan (issue 22).

For each size n and seed the problem's start and goal states are drawn uniformly at random
(Slaney and Thiebaux's exact method, bench/planning/bw_problems.py); the goal is the goal state's
`on` facts, as the IPC Blocks World problems state it. Each problem is written as PDDL for the
four-operator domain (bench/planning/bw_pddl.py) and solved by pyperplan, greedy best-first with
h_FF and A* with LM-cut, each in a subprocess killed at its time limit; and as a scenario of the
pymunk Blocks World (world/blocks), run by `teleo simulate`'s loop in this process for
10 n + 20 cycles with the goal given three ways: one goal for the conjunction, and one user
goal per literal in priority order, each tower top-down (as IPC lists them) or bottom-up
(bench/planning/bw_teleo.py). Every teleo run is checked on its own (bench/planning/bw_check.py):
its actions replayed under STRIPS rules from the start, the goal checked on the result and every
goal its summary calls achieved; a run that fails is not solved and is printed. Then the learning
curve: the problems in order, each from the skills the ones before it learned, and held-out
problems of every size fresh and with the curve's final skills. Last, issue 22's targets,
each met or NOT MET with the problems that miss it. Once pyperplan has timed out on every
seed of a size it is not run on larger ones (--no-skip runs it anyway).

Run: .venv/bin/python bench/planning/planning.py [--sizes 3-30] [--seeds 1-5] [--held-out 6-7]
     [--gbf-limit 30] [--astar-limit 20] [--jobs 2] [--keep DIR] [--quick]
"""

from __future__ import annotations

import datetime
import os
import platform
import shlex
import subprocess
import sys
import tempfile
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from importlib.metadata import version
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bench.planning import bw_report, bw_targets, bw_tasks, bw_teleo  # noqa: E402
from bench.planning.bw_pyperplan import PLANNERS  # noqa: E402
from bench.planning.bw_report import MAIN  # noqa: E402

MAX_N = 30


def numbers(text: str, what: str, lo: int, hi: int) -> list[int]:
    """"3-6,10" as [3, 4, 5, 6, 10]; raises click.BadParameter naming ``what``."""
    out: list[int] = []
    for part in text.split(","):
        a, sep, b = part.strip().partition("-")
        try:
            first, last = int(a), int(b) if sep else int(a)
        except ValueError:
            raise click.BadParameter(f"expected numbers or ranges such as 3-6,10, got "
                                     f"{part.strip()!r}", param_hint=what) from None
        if not lo <= first <= last <= hi:
            raise click.BadParameter(f"expected {lo}..{hi} (a range low-high), got "
                                     f"{part.strip()!r}", param_hint=what)
        out += [x for x in range(first, last + 1) if x not in out]
    return out


class Scheduler:
    """A process pool kept to ``jobs`` tasks at a time: pyperplan's, released size by size,
    go before teleo's; a task's result goes to ``done``."""

    def __init__(self, pool: ProcessPoolExecutor, jobs: int) -> None:
        self.pool, self.jobs = pool, jobs
        self.first: deque = deque()
        self.rest: deque = deque()
        self.running: dict = {}

    def add(self, tag: tuple, fn, *args, urgent: bool = False) -> None:
        (self.first if urgent else self.rest).append((tag, fn, args))

    def run(self, done) -> None:
        while self.first or self.rest or self.running:
            while len(self.running) < self.jobs and (self.first or self.rest):
                tag, fn, args = (self.first or self.rest).popleft()
                self.running[self.pool.submit(fn, *args)] = tag
            finished, _ = wait(self.running, return_when=FIRST_COMPLETED)
            for future in finished:
                done(self.running.pop(future), future.result(), self)


def run_all(opts: dict, folder: str) -> bw_report.Results:
    res = bw_report.Results(opts["sizes"], opts["seeds"], opts["held_out"])
    limits = {"gbf-hff": opts["gbf_limit"], "astar-lmcut": opts["astar_limit"]}
    sizes = deque(opts["sizes"])
    given_up: dict[str, int] = {}

    def release(s: Scheduler) -> None:
        """The pyperplan tasks of the next size that has any (every planner may be skipped)."""
        while sizes:
            n = sizes.popleft()
            for planner in PLANNERS:
                if planner in given_up and not opts["no_skip"]:
                    res.skipped[(n, planner)] = (f"timed out on every seed at n = "
                                                 f"{given_up[planner]}")
                    continue
                for key in res.keys(n):
                    s.add(("plan", key, planner), bw_tasks.plan, key, planner, folder,
                          limits[planner], urgent=True)
            if any((n, p) not in res.skipped for p in PLANNERS):
                return

    def done(tag: tuple, result, s: Scheduler) -> None:
        kind = tag[0]
        if kind == "plan":
            res.plans[(tag[1], tag[2])] = result
            n = tag[1][0]
            if all((k, p) in res.plans for k in res.keys(n) for p in PLANNERS
                   if (n, p) not in res.skipped):
                for p in PLANNERS:
                    if (n, p) not in res.skipped and p not in given_up and all(
                            res.plans[(k, p)].status == "timeout" for k in res.keys(n)):
                        given_up[p] = n
                release(s)
        elif kind == "teleo":
            res.teleo[(tag[1], tag[2])] = result
        elif kind == "curve":
            res.curve, learned = result
            for key in heldout:
                s.add(("skilled", key), bw_tasks.teleo, key, MAIN, folder, learned)
        else:
            (res.fresh if kind == "fresh" else res.skilled)[tag[1]] = result
        progress[0] += 1
        if progress[0] % 25 == 0:
            click.echo(f"... {progress[0]} tasks done", err=True)

    training = [k for n in opts["sizes"] for k in res.keys(n)]
    heldout = [(n, s) for n in opts["sizes"] for s in opts["held_out"]]
    progress = [0]
    with ProcessPoolExecutor(max_workers=opts["jobs"]) as pool:
        s = Scheduler(pool, opts["jobs"])
        s.add(("curve",), bw_tasks.curve, training, MAIN, folder)
        release(s)
        for key in training:
            for mode in bw_teleo.MODES:
                s.add(("teleo", key, mode), bw_tasks.teleo, key, mode, folder)
        for key in heldout:
            s.add(("fresh", key), bw_tasks.teleo, key, MAIN, folder)
        s.run(done)
    return res


def header(opts: dict, argv: list[str]) -> list[str]:
    commit = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    goal = "(and ...)" if bw_teleo.CONJUNCTION_SYNTAX else \
        "the program's concept (goal-state) :relations (the literals) (no (and ...) yet)"
    return [
        f"planning bench (issue 22): {datetime.datetime.now().isoformat(timespec='seconds')}, "
        f"teleo {commit}, pyperplan {version('pyperplan')}, python {platform.python_version()}",
        f"machine: {platform.node()}, {os.cpu_count()} cpus, load average "
        f"{' '.join(f'{x:.2f}' for x in os.getloadavg())} at the start; jobs {opts['jobs']}",
        f"command: {' '.join(shlex.quote(a) for a in argv)}",
        f"sizes n = {','.join(map(str, opts['sizes']))}; seeds "
        f"{','.join(map(str, opts['seeds']))} (problem bw-n-seed); held-out seeds "
        f"{','.join(map(str, opts['held_out']))}",
        f"pyperplan limits: gbf-hff {opts['gbf_limit']:g} s, astar-lmcut "
        f"{opts['astar_limit']:g} s; teleo: 10 n + 20 cycles, the conjunction given as {goal}",
    ]


@click.command(context_settings={"help_option_names": ["-h", "--help"]})
@click.option("--sizes", default="3-30", show_default=True, help="Block counts, e.g. 3-8,12.")
@click.option("--seeds", default="1-5", show_default=True, help="Problem seeds per size.")
@click.option("--held-out", "held_out", default="6-7", show_default=True,
              help="Seeds of the held-out problems per size (none of --seeds).")
@click.option("--gbf-limit", type=click.FloatRange(min=1, max=3600), default=30.0,
              show_default=True, help="Time limit of greedy best-first h_FF [s].")
@click.option("--astar-limit", type=click.FloatRange(min=1, max=3600), default=20.0,
              show_default=True, help="Time limit of A* LM-cut [s].")
@click.option("--jobs", type=click.IntRange(1, 64), default=2, show_default=True,
              help="Processes at once.")
@click.option("--no-skip", is_flag=True, help="Run pyperplan at every size, even after it "
              "timed out on every seed of a smaller one.")
@click.option("--keep", type=click.Path(file_okay=False, path_type=Path), default=None,
              help="Keep the PDDL, scenarios, programs and learned files in this folder.")
@click.option("--quick", is_flag=True, help="A quick run: sizes 3-4, seeds 1-2, held-out "
              "seed 3, limits 10 s (for a test).")
def main(sizes: str, seeds: str, held_out: str, gbf_limit: float, astar_limit: float,
         jobs: int, no_skip: bool, keep: Path | None, quick: bool) -> None:
    """Random Blocks World problems: teleo against pyperplan, and teleo's learning curve."""
    if quick:
        sizes, seeds, held_out = "3-4", "1-2", "3"
        gbf_limit, astar_limit = min(gbf_limit, 10.0), min(astar_limit, 10.0)
    opts = {"sizes": numbers(sizes, "--sizes", 2, MAX_N),
            "seeds": numbers(seeds, "--seeds", 0, 10**6),
            "held_out": numbers(held_out, "--held-out", 0, 10**6),
            "gbf_limit": gbf_limit, "astar_limit": astar_limit, "jobs": jobs,
            "no_skip": no_skip}
    common = sorted(set(opts["seeds"]) & set(opts["held_out"]))
    if common:
        raise click.BadParameter(f"seeds {common} are training seeds too", param_hint="--held-out")
    lines = header(opts, ["bench/planning/planning.py", *sys.argv[1:]])
    click.echo("\n".join(lines))
    if keep is not None:
        keep.mkdir(parents=True, exist_ok=True)
        res = run_all(opts, str(keep.resolve()))
    else:
        with tempfile.TemporaryDirectory(prefix="teleo-planning-") as folder:
            res = run_all(opts, folder)
    out = [*bw_report.conjunction_table(res), *bw_report.orders_table(res, "conjunction"),
           *bw_report.orders_table(res, "list"),
           *bw_report.curve_table(res), *bw_report.held_out_table(res)]
    if res.skipped:
        out += ["", "pyperplan not run: " + "; ".join(
            f"{p} at n >= {n}: {why}" for (n, p), why in sorted(res.skipped.items())
            if not _prev(res.sizes, n) or (_prev(res.sizes, n), p) not in res.skipped)]
    out += [*bw_targets.invalid_runs(res), *bw_targets.targets(res), "",
            f"load average at the end: {' '.join(f'{x:.2f}' for x in os.getloadavg())}"]
    click.echo("\n".join(out))


def _prev(sizes: list[int], n: int) -> int:
    """The size run before n (0 for the first)."""
    k = sizes.index(n)
    return sizes[k - 1] if k else 0


if __name__ == "__main__":
    main()
