"""A burst of goal requests against a running launch: does it slow the run? (fault drill 4d, O5)

    .venv/bin/python bench/faults/goal_burst.py [--requests 1200] [--clients 1] [--window 5]

It launches SCENARIO (lockstep, endless), measures the cycle rate for WINDOW seconds, then
sends REQUESTS goal requests as fast as one client can (the drill's mix: valid posts of
goals nobody can achieve, 1 MB goals, priorities up to 2^64-1, cancels, reprioritisations,
lists and junk), and measures the rate during the burst and for WINDOW seconds after it.
Printed: cycles/s before, during and after, the ratio after/before (the drill, before the
limits: 441 -> 42 cycles/s, 0.10), the replies (ok, refused, unanswered), reply times, the
goal store's size, and each process's mean compute time per cycle before and after.
"""

from __future__ import annotations

import os
import random
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))  # `bus` is the package, not bench/speed/bus.py


def cycles_done(run_dir: Path) -> int:
    """Cycles the world has traced so far (one line each)."""
    path = run_dir / "trace.jsonl"
    return path.read_bytes().count(b"\n") if path.exists() else 0


def measure(run_dir: Path, endpoint: str, run: str, seconds: float) -> tuple[float, dict]:
    """Cycles per second over the next `seconds`, and each process's mean compute time per
    cycle [ms] from its ProcessStats."""
    from bus import keys
    from bus.config import BusConfig
    from bus.node import open_node
    from bus.stats import stats_of

    cfg = BusConfig(mode="client", connect=(endpoint,), listen=())
    with open_node(cfg, run, "burst-stats") as node:
        # stats alone (the goals stage, the world, a stage gone idle) and those each agent's
        # Actions carry for its pipeline (bus/stats.py); one figure per process and cycle
        rings = [node.subscribe_ring(k, capacity=200_000)
                 for k in (keys.all_stats(run), keys.all_actions(run))]
        start, t0 = cycles_done(run_dir), time.monotonic()
        time.sleep(seconds)
        cycles_per_s = (cycles_done(run_dir) - start) / (time.monotonic() - t0)
        seen: dict[tuple[str, int], float] = {}
        for ring in rings:
            for got in ring.drain():
                for s in stats_of(got.msg):
                    seen.setdefault((s.process, s.env.cycle), s.compute_ms)
        per: dict[str, list[float]] = {}
        for (process, _), ms in seen.items():
            per.setdefault(process, []).append(ms)
    return cycles_per_s, {p: statistics.mean(v) for p, v in sorted(per.items())}


def request_mix(n: int, agent: str, seed: int, mix: str) -> list[tuple[str, str, int, str]]:
    """(op, goal, priority, goal_id) of drill 4d: mostly posts, some huge, some junk; or, for
    mix "posts", only posts of goals nobody can achieve, all at priority 1 (the costliest)."""
    rng = random.Random(seed)
    if mix == "posts":
        return [("post", f"(package-delivered P{i})", 1, "") for i in range(n)]
    out = []
    for i in range(n):
        kind = rng.random()
        if kind < 0.5:
            out.append(("post", f"(package-delivered P{i})", rng.randint(1, 200), ""))
        elif kind < 0.55:
            out.append(("post", "(package-delivered " + "X" * 1_000_000 + ")", 5, ""))
        elif kind < 0.6:
            out.append(("post", f"(package-delivered Q{i})", 2**64 - 1, ""))
        elif kind < 0.7:
            out.append(("cancel", "", 0, f"g{rng.randint(1, n)}"))
        elif kind < 0.8:
            out.append(("priority", "", rng.randint(-5, 10**9), f"g{rng.randint(1, n)}"))
        elif kind < 0.9:
            out.append(("list", "", 0, ""))
        else:
            junk = "".join(rng.choice("() ?xyz19.e-") for _ in range(rng.randint(0, 40)))
            out.append(("post", junk, rng.randint(1, 10), ""))
    return out


def burst(endpoint: str, run: str, agent: str, requests: list, clients: int) -> dict:
    """Send every request, one after another, from `clients` sender names in turn (one
    session); count the answers and time them [ms]."""
    from bus import keys
    from bus.config import BusConfig
    from bus.errors import BusError
    from bus.messages import GoalRequest
    from bus.node import open_node

    counts = {"ok": 0, "refused": 0, "unanswered": 0}
    times = []
    cfg = BusConfig(mode="client", connect=(endpoint,), listen=())
    with open_node(cfg, run, "burst") as node:
        for i, (op, goal, priority, goal_id) in enumerate(requests):
            env = replace(node.envelope(), sender=f"burst{i % clients}")
            t0 = time.perf_counter()
            try:
                reply = node.query(keys.goals(run, agent),
                                   GoalRequest(env, op, agent, goal, priority, goal_id), 5.0)
                counts["ok" if reply.ok else "refused"] += 1
            except BusError:
                counts["unanswered"] += 1
            times.append((time.perf_counter() - t0) * 1e3)
    return {"counts": counts, "times": times}


@click.command()
@click.option("--requests", default=1200, type=click.IntRange(min=1), show_default=True,
              help="Requests in the burst.")
@click.option("--window", default=5.0, type=click.FloatRange(min=0, min_open=True),
              show_default=True, help="Seconds measured before/after.")
@click.option("--scenario", default=str(ROOT / "scenarios" / "driving_demo.toml"),
              show_default=True, type=click.Path(exists=True))
@click.option("--seed", default=4, show_default=True, help="Seed of the request mix.")
@click.option("--clients", default=1, show_default=True,
              help="Sender names the requests take in turn (each is a client to the limits).")
@click.option("--mix", type=click.Choice(["drill", "posts"]), default="drill", show_default=True,
              help="drill: drill 4d's mix; posts: unachievable goals at priority 1.")
def main(requests: int, window: float, scenario: str, seed: int, clients: int,
         mix: str) -> None:
    """Measure the cycle rate before, during and after a burst of goal requests."""
    from tools.runs import runfile

    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "TELEO_RUN_DIR": tmp}
        teleo = str(Path(sys.executable).parent / "teleo")
        launcher = subprocess.Popen([teleo, "launch", scenario, "--cycles", "0", "--mode",
                                     "lockstep"], cwd=ROOT, env=env, stdout=subprocess.DEVNULL,
                                    stderr=subprocess.DEVNULL)
        try:
            os.environ["TELEO_RUN_DIR"] = tmp
            end = time.monotonic() + 120
            while True:
                try:
                    info = runfile.find()
                    break
                except runfile.NoRunningLaunch:
                    if time.monotonic() > end or launcher.poll() is not None:
                        raise click.ClickException("the launch did not start") from None
                    time.sleep(0.1)
            run_dir = Path(info.run_dir)
            time.sleep(1.0)  # past start-up
            before, ms_before = measure(run_dir, info.endpoint, info.run, window)
            c0, t0 = cycles_done(run_dir), time.monotonic()
            result = burst(info.endpoint, info.run, info.agents[0],
                           request_mix(requests, info.agents[0], seed, mix), clients)
            during = (cycles_done(run_dir) - c0) / (time.monotonic() - t0)
            burst_s = time.monotonic() - t0
            after, ms_after = measure(run_dir, info.endpoint, info.run, window)
            store = run_dir / "goals.json"
            size = store.stat().st_size if store.exists() else 0
        finally:
            launcher.send_signal(signal.SIGINT)
            launcher.wait(60)
    times = sorted(result["times"]) or [0.0]
    c = result["counts"]
    click.echo(f"goal burst: {requests} requests ({mix}) from {clients} client(s) in "
               f"{burst_s:.1f} s against {Path(scenario).name}")
    click.echo(f"  cycles/s before {before:.1f}, during {during:.1f}, after {after:.1f}; "
               f"after/before {after / before:.2f}")
    click.echo(f"  replies: {c['ok']} ok, {c['refused']} refused, {c['unanswered']} unanswered")
    click.echo(f"  reply time [ms]: median {statistics.median(times):.1f}, "
               f"p99 {times[max(int(len(times) * 0.99) - 1, 0)]:.1f}, max {times[-1]:.1f}")
    click.echo(f"  goals.json: {size} bytes")
    click.echo("  compute per cycle [ms], before -> after: " + ", ".join(
        f"{p} {ms_before.get(p, 0.0):.2f} -> {ms_after.get(p, 0.0):.2f}" for p in ms_after))


if __name__ == "__main__":
    main()
