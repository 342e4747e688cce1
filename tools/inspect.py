"""`teleo inspect`: a live terminal view of a running launch.

Shows the processes and their liveliness (with how many times each appeared, so restarts
show), every key of the run with its message rate, payload size and cycle latency (time
from the world state of that cycle to this message), each stage's compute time and late
count, and the decoded last message of a chosen key. `--once` / `--seconds N` watch for a
while and print the tables once (for scripts and tests); without them it refreshes live
until Ctrl-C.
"""

from __future__ import annotations

import json
import time
from collections import deque
from dataclasses import asdict, dataclass, field, is_dataclass
from typing import Any

import click
from rich.console import Console, Group
from rich.live import Live
from rich.table import Table
from rich.text import Text

from tools import runfile

WINDOW_S = 5.0  # [s] over which rates are computed


@dataclass
class KeyStats:
    """What has been seen on one key."""

    count: int = 0
    size: int = 0
    last_cycle: int = -1
    latency_ms: float | None = None
    times: deque = field(default_factory=lambda: deque(maxlen=1000))
    last: Any = None

    def rate(self, now_ns: int) -> float:
        """Messages per second over the last WINDOW_S [1/s]."""
        recent = [t for t in self.times if now_ns - t <= WINDOW_S * 1e9]
        if len(recent) < 2:
            return 0.0
        span = (recent[-1] - recent[0]) / 1e9
        return (len(recent) - 1) / span if span > 0 else 0.0


class Model:
    """Pure bookkeeping of the inspector: fed with received samples, read by the views."""

    def __init__(self, run: str) -> None:
        self.run = run
        self.prefix = f"teleo/{run}/"
        self.keys: dict[str, KeyStats] = {}
        self.state_sent: dict[int, int] = {}  # cycle -> world state sent_ns
        self.stages: dict[str, dict[str, float]] = {}

    def feed(self, key: str, msg: Any, payload: bytes, t_ns: int) -> None:
        short = key[len(self.prefix):] if key.startswith(self.prefix) else key
        stats = self.keys.setdefault(short, KeyStats())
        stats.count += 1
        stats.size = len(payload)
        stats.times.append(t_ns)
        stats.last = msg
        env = getattr(msg, "env", None)
        if env is None:
            return
        stats.last_cycle = env.cycle
        if short == "world/state":
            self.state_sent[env.cycle] = env.sent_ns
            if len(self.state_sent) > 200:
                del self.state_sent[min(self.state_sent)]
        if env.cycle in self.state_sent:
            stats.latency_ms = (env.sent_ns - self.state_sent[env.cycle]) / 1e6
        if type(msg).__name__ == "ProcessStats":
            self.stages[msg.process] = {"compute_ms": msg.compute_ms, "late": msg.late,
                                        "cycle": env.cycle}

    def decoded(self, suffix: str) -> str:
        """The last message on the key ending with `suffix`, as indented JSON."""
        for short, stats in sorted(self.keys.items()):
            if short.endswith(suffix):
                return f"{short}:\n{json.dumps(_plain(stats.last), indent=1, default=str)}"
        return f"nothing seen yet on a key ending with {suffix!r}"


def _plain(msg: Any) -> Any:
    return asdict(msg) if is_dataclass(msg) else msg


def render(model: Model, alive: set[str], incarnations: dict[str, int],
           key: str | None) -> Group:
    """The view: processes, keys, and optionally one decoded message."""
    now = time.time_ns()
    procs = Table(title=f"run {model.run}: processes")
    for col in ("process", "live", "appeared", "cycle", "compute ms", "late"):
        procs.add_column(col)
    for name in sorted(set(incarnations) | set(model.stages) | alive):
        st = model.stages.get(name, {})
        procs.add_row(name, "up" if name in alive else "GONE", str(incarnations.get(name, 0)),
                      str(int(st["cycle"])) if st else "-",
                      f"{st['compute_ms']:.2f}" if st else "-",
                      str(int(st["late"])) if st else "-")
    table = Table(title="keys")
    for col in ("key", "msgs", "rate /s", "bytes", "cycle", "latency ms"):
        table.add_column(col)
    for short, s in sorted(model.keys.items()):
        lat = "-" if s.latency_ms is None else f"{s.latency_ms:.2f}"
        table.add_row(short, str(s.count), f"{s.rate(now):.1f}", str(s.size),
                      str(s.last_cycle), lat)
    parts: list[Any] = [procs, table]
    if key:
        parts.append(Text(model.decoded(key)))
    return Group(*parts)


@click.command()
@click.option("--key", "-k", help="Show the decoded last message of the key ending with this, "
                                  "e.g. agent/ME/intention.")
@click.option("--once", is_flag=True, help="Watch 2 s, print the tables once, exit.")
@click.option("--seconds", type=float, help="Watch this long [s], print once, exit.")
@runfile.run_option
def inspect(key: str | None, once: bool, seconds: float | None, run_id: str | None) -> None:
    """Live view of the running launch: processes, keys, rates, latency, late stages."""
    from bus import keys
    from bus.node import open_node

    info = runfile.locate(run_id)
    cfg = runfile.bus_config(info)
    model = Model(info.run)
    watch = seconds if seconds is not None else (2.0 if once else None)
    with open_node(cfg, info.run, "inspect") as node:
        inbox = node.subscribe(keys.run_all(info.run))
        presence = node.presence

        def pump(until: float) -> None:
            while (left := until - time.monotonic()) > 0:
                item = inbox.receive(min(left, 0.05))
                if item is not None:
                    model.feed(item.key, item.msg, item.payload, item.t_ns)

        def view() -> Group:
            return render(model, set(presence.snapshot()), presence.incarnations(), key)

        if watch is not None:
            pump(time.monotonic() + watch)
            Console(width=160).print(view())
            return
        try:
            with Live(view(), refresh_per_second=4) as live:
                while True:
                    pump(time.monotonic() + 0.25)
                    live.update(view())
        except KeyboardInterrupt:
            pass


commands = [inspect]
