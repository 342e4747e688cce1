"""`teleo inspect`: a live terminal view of a running launch.

Shows the processes and their liveliness (how many times each appeared while watched, and
how many times the launcher restarted it, from the run file), every key of the run with its
message rate, payload size and two latencies, each stage's compute time and late count
(the world's too: it publishes its own stats), and the decoded last message of a chosen key.
`--once` / `--seconds N` watch for a while and print the tables once (for scripts and tests);
without them it refreshes live until Ctrl-C.

Latencies are measured by arrival here, on one clock, not from the senders' stamps: a world
state is stamped before the realtime clock's pacing wait (up to a period), so stamps would show the
wait, not the pipeline. "latency ms" is the time from the arrival of the world state of a
message's cycle to the message's; "stage ms" the time from the arrival of its input of the
same cycle (percepts <- world state, beliefs <- percepts, actions and intention <- beliefs):
what that stage and the bus hop to it took.
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

from tools.runs import runfile

WINDOW_S = 5.0  # [s] over which rates are computed


@dataclass
class KeyStats:
    """What has been seen on one key."""

    count: int = 0
    size: int = 0
    last_cycle: int = -1
    latency_ms: float | None = None   # since the world state of its cycle arrived [ms]
    stage_ms: float | None = None     # since its input of the same cycle arrived [ms]
    times: deque = field(default_factory=lambda: deque(maxlen=1000))
    last: Any = None

    def rate(self, now_ns: int) -> float:
        """Messages per second over the last WINDOW_S [1/s]."""
        recent = [t for t in self.times if now_ns - t <= WINDOW_S * 1e9]
        if len(recent) < 2:
            return 0.0
        span = (recent[-1] - recent[0]) / 1e9
        return (len(recent) - 1) / span if span > 0 else 0.0


# The key (short form) each agent key's stage reads, by its leaf.
_INPUT = {"percepts": "world/state", "beliefs": "percepts", "actions": "beliefs",
          "intention": "beliefs", "goal-list": "world/state"}
_KEPT_CYCLES = 200


def upstream(short: str) -> str | None:
    """The short key of the input a key's message of cycle t is computed from, or None."""
    parts = short.split("/")
    if len(parts) == 3 and parts[0] == "agent" and parts[2] in _INPUT:
        leaf = _INPUT[parts[2]]
        return leaf if "/" in leaf else f"agent/{parts[1]}/{leaf}"
    return None


class Model:
    """Pure bookkeeping of the inspector: fed with received samples, read by the views."""

    def __init__(self, run: str) -> None:
        self.run = run
        self.prefix = f"teleo/{run}/"
        self.keys: dict[str, KeyStats] = {}
        self.arrived: dict[int, dict[str, int]] = {}  # cycle -> short key -> arrival [ns]
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
        self._arrival(short, stats, env.cycle, t_ns)
        from bus.stats import stats_of  # bus is loaded by the command (fast --help)

        for st in stats_of(msg, own=True):  # a ProcessStats, or those an output carries
            self.stages[st.process] = {"compute_ms": st.compute_ms, "late": st.late,
                                       "cycle": env.cycle}

    def _arrival(self, short: str, stats: KeyStats, cycle: int, t_ns: int) -> None:
        """Note when `short`'s message of `cycle` arrived; set its two latencies."""
        if cycle < 0:
            return
        seen = self.arrived.setdefault(cycle, {})
        seen.setdefault(short, t_ns)
        if len(self.arrived) > _KEPT_CYCLES:
            del self.arrived[min(self.arrived)]
        state = seen.get("world/state")
        if state is not None:
            stats.latency_ms = (t_ns - state) / 1e6
        before = seen.get(upstream(short) or "")
        if before is not None:
            stats.stage_ms = (t_ns - before) / 1e6

    def decoded(self, suffix: str) -> str:
        """The last message on the key ending with `suffix`, as indented JSON."""
        for short, stats in sorted(self.keys.items()):
            if short.endswith(suffix):
                return f"{short}:\n{json.dumps(_plain(stats.last), indent=1, default=str)}"
        return f"nothing seen yet on a key ending with {suffix!r}"


def _ms(value: float | None) -> str:
    return "-" if value is None else f"{value:.2f}"


def _plain(msg: Any) -> Any:
    return asdict(msg) if is_dataclass(msg) else msg


def render(model: Model, alive: set[str], incarnations: dict[str, int],
           key: str | None, restarts: dict[str, int] | None = None) -> Group:
    """The view: processes, keys, and optionally one decoded message. `restarts`: how many
    times the launcher restarted each process (the run file's)."""
    now = time.time_ns()
    restarts = restarts or {}
    procs = Table(title=f"run {model.run}: processes")
    for col in ("process", "live", "appeared", "restarts", "cycle", "compute ms", "late"):
        procs.add_column(col)
    for name in sorted(set(incarnations) | set(model.stages) | alive | set(restarts)):
        st = model.stages.get(name, {})
        procs.add_row(name, "up" if name in alive else "GONE", str(incarnations.get(name, 0)),
                      str(restarts.get(name, 0)), str(int(st["cycle"])) if st else "-",
                      f"{st['compute_ms']:.2f}" if st else "-",
                      str(int(st["late"])) if st else "-")
    table = Table(title="keys (latency: since the world state of the cycle arrived; "
                        "stage: since the stage's input arrived)")
    for col in ("key", "msgs", "rate /s", "bytes", "cycle", "latency ms", "stage ms"):
        table.add_column(col)
    for short, s in sorted(model.keys.items()):
        table.add_row(short, str(s.count), f"{s.rate(now):.1f}", str(s.size),
                      str(s.last_cycle), _ms(s.latency_ms), _ms(s.stage_ms))
    parts: list[Any] = [procs, table]
    if key:
        parts.append(Text(model.decoded(key)))
    return Group(*parts)


@click.command()
@click.option("--key", "-k", help="Show the decoded last message of the key ending with this, "
                                  "e.g. agent/ME/intention.")
@click.option("--once", is_flag=True, help="Watch 2 s, print the tables once, exit.")
@click.option("--seconds", type=click.FloatRange(min=0, min_open=True),
              help="Watch this long [s], print once, exit.")
@runfile.run_option
@runfile.quiet_option
def inspect(key: str | None, once: bool, seconds: float | None, run_id: str | None) -> None:
    """Live view of the running launch: processes, keys, rates, latency.

    Restarts and late stages too; --once or --seconds print once for scripts."""
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
            return render(model, set(presence.snapshot()), presence.incarnations(), key,
                          _restarts(info))

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


def _restarts(info: runfile.RunInfo) -> dict[str, int]:
    """The launcher's restart counts, read afresh from the run file (the last known once the
    launch is gone)."""
    try:
        current = runfile.find(info.run)
    except runfile.NoRunningLaunch:
        return dict(info.restarts)
    return dict(current.restarts if current.run == info.run else info.restarts)


commands = [inspect]
