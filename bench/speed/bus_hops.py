"""What the codec costs at each hop of bench/speed/bus.py's pass-through cycle, in one process
without zenoh: the CPU time of every decode and encode the clock and the three stages do to one
cycle's messages (200 percepts shaped like the driving domain's, bus/passthrough.py `percepts_200`).

    .venv/bin/python bench/speed/bus_hops.py [--cycles 2000]

The stages' rows are new lists each cycle, as they are in the bench (the perception stage takes
them from the decoded world state), so every row is packed again where a stage sends them on.
Prints the median of each step [ms, this thread's CPU time], their sum per cycle and the
payload sizes: the part of bench/speed/bus.py's cycle above its raw four hops that is the codec.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bus import keys  # noqa: E402
from bus.codec import decode, encode  # noqa: E402
from bus.messages import Actions, Beliefs, Envelope, Percepts, ProcessStats, WorldState  # noqa: E402
from bus.passthrough import percepts_200  # noqa: E402

RUN, AGENT = "bench", "A"


@click.command()
@click.option("--cycles", type=click.IntRange(min=10), default=2000, show_default=True)
def main(cycles: int) -> None:
    """Print the codec's CPU time per hop of one pass-through cycle."""
    tick = time.thread_time
    steps = ("world state: encode (clock)", "world state: decode (perception)",
             "percepts: encode (perception)", "percepts: decode (inference)",
             "beliefs: encode (inference)", "beliefs: decode (executive)",
             "actions: encode (executive)", "actions: decode (clock)",
             "3 stats: encode (stages)")
    spent: dict[str, list[float]] = {s: [] for s in steps}
    rows, sizes = percepts_200(), {}
    for c in range(cycles):
        t = [tick()]
        ws = encode(WorldState(Envelope.now(RUN, c, "world"), {"percepts": {AGENT: rows}},
                               {}, []))
        t.append(tick())
        state = decode(keys.world_state(RUN), ws)
        t.append(tick())
        p = encode(Percepts(Envelope.now(RUN, c, "A.perception"), AGENT,
                            tuple(state.snapshot["percepts"][AGENT])))
        t.append(tick())
        seen = decode(keys.percepts(RUN, AGENT), p)
        t.append(tick())
        b = encode(Beliefs(Envelope.now(RUN, c, "A.inference"), AGENT, seen.percepts))
        t.append(tick())
        believed = decode(keys.beliefs(RUN, AGENT), b)
        t.append(tick())
        a = encode(Actions(Envelope.now(RUN, c, "A.executive"), AGENT,
                           (["*pass", c, len(believed.beliefs)],)))
        t.append(tick())
        decode(keys.actions(RUN, AGENT), a)
        t.append(tick())
        for stage in ("perception", "inference", "executive"):
            encode(ProcessStats(Envelope.now(RUN, c, f"A.{stage}"), f"A.{stage}", 0.1, 0))
        t.append(tick())
        for s, t0, t1 in zip(steps, t[:-1], t[1:], strict=True):
            spent[s].append((t1 - t0) * 1e3)
        sizes = {"world state": len(ws), "percepts": len(p), "beliefs": len(b)}
    total = 0.0
    for s in steps:
        ms = statistics.median(spent[s])
        total += ms
        click.echo(f"{s:<34} {ms:.4f} ms")
    click.echo(f"{'the codec, one cycle':<34} {total:.4f} ms (CPU, medians summed)")
    click.echo("payload bytes: " + ", ".join(f"{k} {v}" for k, v in sizes.items()))


if __name__ == "__main__":
    main()
