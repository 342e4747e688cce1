"""zenoh's shared-memory transport against plain puts, between two processes on this host
(issue 27): the round trip of one payload sent as bytes with shared memory disabled, as bytes
with zenoh's default (shared memory enabled: a put of 3 KB or more is copied into it by the
transport; teleo's processes run so today), and in a shared-memory buffer of its own, for
the demo's message size (about 15 KB: a world state, percepts or beliefs, bench/speed/bus_hops.py)
and a larger one; the modes alternate in rounds, each median set against today's.

    .venv/bin/python bench/speed/bus_shm.py [--sizes 15000,1000000] [--n 500] [--rounds 3]
"""

from __future__ import annotations

import statistics
import sys
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bus.shm_probe import round_trips  # noqa: E402


@click.command()
@click.option("--sizes", default="15000,1000000", show_default=True,
              help="Payload sizes [bytes], comma-separated.")
@click.option("--n", type=click.IntRange(min=10), default=500, show_default=True,
              help="Round trips a measurement.")
@click.option("--rounds", type=click.IntRange(min=1), default=3, show_default=True)
def main(sizes: str, n: int, rounds: int) -> None:
    """Print the median round trip [ms] of bytes and of shared memory, and their ratio."""
    try:
        wanted = [int(s) for s in sizes.split(",")]
    except ValueError:
        raise click.BadParameter(f"expected sizes such as 15000,1000000, got {sizes!r}",
                                 param_hint="--sizes") from None
    for size in wanted:
        modes = (("bytes, shared memory disabled", False, False),
                 ("bytes, zenoh's default (today)", False, True),
                 ("a shared-memory buffer", True, True))
        times: dict[str, list[float]] = {m: [] for m, _, _ in modes}
        came = dict.fromkeys(times, 0)
        for _ in range(rounds):
            for mode, shm, enabled in modes:
                got, in_shm = round_trips(size, n, shm, enabled)
                times[mode] += got
                came[mode] += in_shm
        today = statistics.median(times[modes[1][0]])
        print(f"{size} bytes ({rounds} x {n} round trips each, alternating):")
        for mode, _, _ in modes:
            ms = statistics.median(times[mode])
            print(f"  {mode:<32} {ms:.3f} ms, {ms / today:.2f}x today; answers in shared "
                  f"memory {came[mode]} of {rounds * (n + 50)}")


if __name__ == "__main__":
    main()
