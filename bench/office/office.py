"""Benchmark: ROGUE's merged order (seed 003, section 4: "ROGUE selects the one that
minimizes the expected total traveled distance from the current location") on random office
request sets, against first-come-first-served and the optimal order.

    .venv/bin/python bench/office/office.py [--sets 40] [--seed 1] [--window 240]

Each set (bench/office/office_sets.py) is 3 to 8 delivery requests of one priority on the default
office floor (random holders, items, destinations and arrival cycles, the robot in a random
room), drawn with random.Random(seed + set number) and run through the planner in this
process (the pymunk office world, perception, the engine with the ROGUE planner) until every
request has ended. Per set, its seed and the travel by the map [m] of teleo's executed order,
of first-come-first-served and of the optimal order (exact branch and bound over the orders
of the visits that keep each request's order, its arrival and the robot's capacity; see
bench/office/office_sets.py), the ratios, the order of least travel for a robot that knew every
request from the start and waited ("clairvoyant"), and whether every request was done once
with no step of it repeated. The last line, for scripts, is one line of this form:

    travel: mean X x optimal, worst Y x optimal, first-come-first-served Z x optimal;
    N of N requests done once

--beam instead compares the planner's two merge searches (agents/lang/planning/merge.py) on
the same sets with the arrivals relaxed: the beam search used beyond MAX_STATES
interleavings against the exact one, as a ratio of their travel.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from agents.lang.planning.merge import Load, Planner  # noqa: E402
from bench.office.office_sets import CONFIG, measure, metric, random_set, run_set  # noqa: E402


def beam_check(sets: int, seed: int, low: int, high: int, window: int) -> None:
    """The merge's beam search against its exact search, per set (arrivals relaxed)."""
    m, ratios = metric(), []
    for k in range(sets):
        s = random_set(seed + k, low, high, window)
        plans = [r.visits() for r in s.requests]
        load = Load(0, CONFIG.capacity, tuple((1, -1) if len(p) == 2 else (0,)
                                              for p in plans))
        exact, beam = Planner(m, plans, load), Planner(m, plans, load)
        exact.exact, beam.exact = True, False
        zero = tuple(0 for _ in plans)
        ratios.append(beam.rest(zero, s.start) / exact.rest(zero, s.start))
    click.echo(f"merge beam search against the exact one, {sets} sets: mean "
               f"{statistics.mean(ratios):.4f} x, worst {max(ratios):.4f} x")


@click.command()
@click.option("--sets", default=40, show_default=True, type=click.IntRange(min=1),
              help="Random request sets.")
@click.option("--seed", default=1, show_default=True, type=int,
              help="Set k is drawn with seed SEED + k.")
@click.option("--window", default=240, show_default=True, type=click.IntRange(min=0),
              help="Requests arrive at cycles 0..WINDOW (the first at 0).")
@click.option("--min", "low", default=3, show_default=True, type=click.IntRange(1, 8),
              help="Fewest requests in a set.")
@click.option("--max", "high", default=8, show_default=True, type=click.IntRange(1, 8),
              help="Most requests in a set.")
@click.option("--beam", is_flag=True, help="Compare the merge's beam and exact searches "
              "instead (no runs).")
def main(sets: int, seed: int, window: int, low: int, high: int, beam: bool) -> None:
    """ROGUE's travel on random office request sets against the optimum and FCFS."""
    if low > high:
        raise click.UsageError(f"--min {low} is above --max {high}")
    if beam:
        beam_check(sets, seed, low, high, window)
        return
    m = metric()
    t0 = time.monotonic()
    click.echo(f"office requests: {sets} sets of {low}-{high} requests, arrivals in cycles "
               f"0..{window}; travel by the map [m]")
    click.echo(f"{'set':>4} {'seed':>6} {'req':>3} {'teleo':>7} {'fcfs':>7} {'optimal':>7} "
               f"{'clairv':>7} {'teleo/opt':>9} {'fcfs/opt':>8} {'once':>5} {'cycles':>6}")
    rows = []
    for k in range(sets):
        s = random_set(seed + k, low, high, window)
        got = measure(s, run_set(s), m)
        rows.append(got)
        proven = "" if got.proven else " (optimum not proven: search budget spent)"
        click.echo(f"{k + 1:>4} {s.seed:>6} {got.requests:>3} {got.teleo:>7.1f} "
                   f"{got.fcfs:>7.1f} {got.optimal:>7.1f} {got.clairvoyant:>7.1f} "
                   f"{got.teleo / got.optimal:>9.3f} {got.fcfs / got.optimal:>8.3f} "
                   f"{got.done_once:>2}/{got.requests:<2} {got.cycles:>6}{proven}")
    worse = [k + 1 for k, r in enumerate(rows) if r.teleo > r.fcfs + 1e-6]
    ratios = [r.teleo / r.optimal for r in rows]
    fcfs = [r.fcfs / r.optimal for r in rows]
    done = sum(r.done_once for r in rows)
    total = sum(r.requests for r in rows)
    click.echo(f"sets worse than first-come-first-served: {len(worse)}"
               + (f" ({' '.join(map(str, worse))})" if worse else "")
               + f"; optimum proven in {sum(r.proven for r in rows)} of {sets}; "
               f"{time.monotonic() - t0:.0f} s")
    click.echo(f"travel: mean {statistics.mean(ratios):.3f} x optimal, worst {max(ratios):.3f} "
               f"x optimal, first-come-first-served {statistics.mean(fcfs):.3f} x optimal; "
               f"{done} of {total} requests done once")


if __name__ == "__main__":
    main()
