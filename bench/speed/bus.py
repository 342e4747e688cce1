"""Bus benchmark: median and p99 of (a) a round trip between two processes and (b) a full
lockstep cycle through the clock and three pass-through stages with 200 percepts.

    .venv/bin/python bench/speed/bus.py [--rounds 2000] [--cycles 500] [--runs 1]

(c) the same four hops forwarding raw bytes is the transport floor; (d) the same lockstep
cycle with the three stages in ONE process (`teleo launch --agents-per-process`): the clock's
two hops, the stages' messages handed over in memory (no decode between stages; still
published, with each stage's stats). The machine is shared and noisy: compare medians of
several runs (`--runs 5`), never single figures.
"""

from __future__ import annotations

import os
import signal
import statistics
import subprocess
import sys
import threading
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from bus import keys  # noqa: E402
from bus.clock import Clock  # noqa: E402
from bus.codec import encode  # noqa: E402
from bus.config import BusConfig, bus_options  # noqa: E402
from bus.messages import Beliefs, Envelope, Percepts, ProcessStats, WorldState  # noqa: E402
from bus.node import open_node  # noqa: E402
from bus.passthrough import STAGES, make_step, percepts_200, wiring  # noqa: E402
from bus.router import spawn_router  # noqa: E402
from bus.stage import Stage  # noqa: E402

RUN, AGENT = "bench", "A"


def figures(name: str, samples_ms: list[float]) -> str:
    s = sorted(samples_ms)
    p99 = s[min(len(s) - 1, int(0.99 * len(s)))]
    return (f"{name}: median {statistics.median(s):.3f} ms, p99 {p99:.3f} ms "
            f"(n={len(s)})")


def spawn(*args: str) -> subprocess.Popen:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.Popen([sys.executable, *args], cwd=ROOT, env=env)


def round_trips(cfg: BusConfig, n: int) -> list[float]:
    pong = spawn(__file__, "pong", *cfg.to_args())
    try:
        with open_node(cfg, RUN, "ping") as node:
            inbox = node.subscribe(keys.beliefs(RUN, AGENT))
            node.declare([keys.percepts(RUN, AGENT)])
            if not node.presence.wait_for(lambda a: "pong" in a, 30):
                raise SystemExit("pong process did not come up")
            node.wait_matching([keys.percepts(RUN, AGENT)], 30)
            out = []
            for i in range(n + 100):
                msg = Percepts(node.envelope(i), AGENT, (["self", "ME", "speed", 20.0],))
                t0 = time.perf_counter()
                node.publish(keys.percepts(RUN, AGENT), msg)
                if inbox.get(timeout=5) is None:
                    raise SystemExit(f"round trip {i} lost")
                if i >= 100:
                    out.append((time.perf_counter() - t0) * 1e3)
            return out
    finally:
        pong.terminate()
        pong.wait(10)


def cycles(cfg: BusConfig, n: int, shared: bool = False) -> list[float]:
    procs = [spawn(__file__, "chain", *cfg.to_args())] if shared else [
        spawn("-m", "bus.passthrough", "--run", RUN, "--agent", AGENT, "--stage", s,
              *cfg.to_args()) for s in STAGES]
    pipeline = [f"{AGENT}.{s}" for s in STAGES]
    snapshot = {"percepts": {AGENT: percepts_200()}}
    try:
        with open_node(cfg, RUN, "world") as node:
            clock = Clock(node, {AGENT: pipeline}, deadline_s=10.0)
            clock.wait_ready(set(pipeline), timeout=30)
            out = []
            for t in range(n + 20):
                t0 = time.perf_counter()
                report = clock.run_cycle(t, WorldState(node.envelope(t), snapshot, {}, []))
                if not report.clean:
                    raise SystemExit(f"cycle {t} not clean: {report}")
                if t >= 20:
                    out.append((time.perf_counter() - t0) * 1e3)
            return out
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            p.wait(10)


@click.group(invoke_without_command=True)
@click.option("--rounds", default=2000, show_default=True)
@click.option("--cycles", "n_cycles", default=500, show_default=True)
@click.option("--runs", default=1, show_default=True,
              help="Repeat everything (fresh processes) and end with the median of the medians.")
@click.pass_context
def main(ctx: click.Context, rounds: int, n_cycles: int, runs: int) -> None:
    if ctx.invoked_subcommand is not None:
        return
    medians: dict[str, list[float]] = {}
    with spawn_router() as router:
        cfg = BusConfig(connect=(router.endpoint,))
        for run in range(runs):
            if runs > 1:
                click.echo(f"-- run {run + 1}/{runs}, load average {os.getloadavg()[0]:.2f}")
            for name, samples in one_run(cfg, rounds, n_cycles):
                click.echo(figures(name, samples))
                medians.setdefault(name, []).append(statistics.median(samples))
    if runs > 1:
        click.echo(f"-- median of the {runs} runs' medians")
        for name, values in medians.items():
            click.echo(f"{name}: {statistics.median(values):.3f} ms "
                       f"(runs: {', '.join(f'{v:.2f}' for v in values)})")


def one_run(cfg: BusConfig, rounds: int, n_cycles: int) -> list[tuple[str, list[float]]]:
    """The three measurements, each with fresh processes: (label, samples [ms])."""
    rt = round_trips(cfg, rounds)
    cyc = cycles(cfg, n_cycles)
    raw = raw_cycles(cfg, n_cycles)
    one = cycles(cfg, n_cycles, shared=True)
    return [("round trip, 2 processes (peers meshed via a router hub)", rt),
            ("lockstep cycle, clock + 3 stages, 200 percepts", cyc),
            ("  same 4 hops, raw bytes forwarded (no codec, no Stage)", raw),
            ("lockstep cycle, clock + the 3 stages in one process", one)]


def raw_cycles(cfg: BusConfig, n: int) -> list[float]:
    """The transport-only floor of the cycle: the same payload forwarded as raw bytes."""
    chain = [keys.world_state(RUN), keys.percepts(RUN, AGENT), keys.beliefs(RUN, AGENT),
             keys.actions(RUN, AGENT)]
    procs = [spawn(__file__, "forward", chain[i], chain[i + 1], f"fwd{i}", *cfg.to_args())
             for i in range(3)]
    env = Percepts(Envelope.now(RUN, 0, "world"), AGENT, ())
    payload = encode(WorldState(env.env, {"percepts": {AGENT: percepts_200()}}, {}, []))
    try:
        with open_node(cfg, RUN, "world-raw") as node:
            inbox = node.subscribe(chain[-1], raw=True)
            node.declare([chain[0]])
            if not node.presence.wait_for(lambda a: {"fwd0", "fwd1", "fwd2"} <= a, 30):
                raise SystemExit("forwarders did not come up")
            node.wait_matching([chain[0]], 30)
            out = []
            for t in range(n + 20):
                t0 = time.perf_counter()
                node.put_raw(chain[0], payload)
                if inbox.receive(timeout=5) is None:
                    raise SystemExit(f"raw cycle {t} lost")
                if t >= 20:
                    out.append((time.perf_counter() - t0) * 1e3)
            return out
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            p.wait(10)


@main.command()
@click.argument("key_in")
@click.argument("key_out")
@click.argument("name")
@bus_options
def forward(key_in: str, key_out: str, name: str, bus_config: BusConfig) -> None:
    """Forward raw payloads from KEY_IN to KEY_OUT (the bare-transport baseline)."""
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    with open_node(bus_config, RUN, name) as node:
        inbox = node.subscribe(key_in, raw=True)
        node.declare([key_out])
        node.wait_matching([key_out], 30)
        node.announce()
        while not stop.is_set():
            item = inbox.receive(0.1)
            if item is not None:
                node.put_raw(key_out, item.payload)


@main.command()
@bus_options
def chain(bus_config: BusConfig) -> None:
    """The three pass-through stages in one process, handing messages over in memory."""
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    names = [f"{AGENT}.{s}" for s in STAGES]
    with open_node(bus_config, RUN, f"{AGENT}.chain") as node:
        steps = [(make_step(node, AGENT, s, None, None), wiring(RUN, AGENT, s)[0],
                  f"{AGENT}.{s}", keys.stats(RUN, f"{AGENT}.{s}")) for s in STAGES]

        def step(cycle: int, inputs: dict) -> list:
            outs, msg = [], inputs[keys.world_state(RUN)]
            for fn, in_key, name, stats_key in steps:
                t0 = time.perf_counter()
                (key, msg), = fn(cycle, {in_key: msg})
                ms = (time.perf_counter() - t0) * 1e3
                outs += [(stats_key, ProcessStats(node.envelope(cycle), name, ms, 0)),
                         (key, msg)]
            return outs

        Stage(node, f"{AGENT}.chain", [keys.world_state(RUN)], step,
              outputs=[keys.actions(RUN, AGENT)], stages=names).run(stop)


@main.command()
@bus_options
def pong(bus_config: BusConfig) -> None:
    """Echo Percepts back as Beliefs (the other end of the round trip)."""
    stop = threading.Event()
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    with open_node(bus_config, RUN, "pong") as node:
        inbox = node.subscribe(keys.percepts(RUN, AGENT))
        node.declare([keys.beliefs(RUN, AGENT)])
        node.wait_matching([keys.beliefs(RUN, AGENT)], 30)
        node.announce()
        while not stop.is_set():
            msg = inbox.get(timeout=0.1)
            if msg is not None:
                node.publish(keys.beliefs(RUN, AGENT),
                             Beliefs(node.envelope(msg.env.cycle), AGENT, msg.percepts))


if __name__ == "__main__":
    main()
