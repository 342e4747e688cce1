"""Message rates on the bus, as `ros2 topic hz`, `bw` and `list -v` give them: `Meter` keeps
what arrived on one key (arrival times and sizes over a window of the last N messages, the
message kinds and publishers seen) and `Figures` is what it says: rate [1/s], the period's
min, max and standard deviation [s], bytes per second and the mean message size [bytes].

Pure bookkeeping, fed with arrival times [ns] by `teleo hz` and `teleo echo --list`
(tools/commands/bus.py), so it is tested on made-up arrivals. Times are when messages
arrived here, on one clock, as ros2 measures them: in lockstep the world's time is not the
wall clock, and a rate of cycles is what a user watching the run wants.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field

DEFAULT_WINDOW = 1000
"""Messages a meter keeps by default [messages]."""


@dataclass(frozen=True)
class Figures:
    """What a meter says about its window: `messages` in it; rate [1/s] (messages after the
    first over the time from the first to the last; 0 with fewer than two); the period's
    min, max, standard deviation [s] (None with fewer than two); bytes per second over the
    same time [bytes/s] and the mean size of a message in the window [bytes]."""

    messages: int
    rate: float
    period_min: float | None
    period_max: float | None
    period_std: float | None
    bytes_per_s: float
    mean_size: float

    def to_dict(self) -> dict[str, float | int | None]:
        return {"messages": self.messages, "rate": self.rate, "period_min": self.period_min,
                "period_max": self.period_max, "period_std": self.period_std,
                "bytes_per_s": self.bytes_per_s, "mean_size": self.mean_size}


@dataclass
class Meter:
    """What arrived on one key: the last `window` arrivals [ns] and sizes [bytes], how many
    in all, and the kinds and publishers (envelope senders) seen."""

    window: int = DEFAULT_WINDOW
    count: int = 0
    kinds: set[str] = field(default_factory=set)
    publishers: set[str] = field(default_factory=set)
    times: deque[int] = field(init=False)
    sizes: deque[int] = field(init=False)

    def __post_init__(self) -> None:
        if self.window < 2:
            raise ValueError(f"a meter's window holds at least 2 messages, got {self.window}")
        self.times = deque(maxlen=self.window)
        self.sizes = deque(maxlen=self.window)

    def feed(self, t_ns: int, size: int, kind: str = "", publisher: str = "") -> None:
        """One message of `size` bytes arrived at `t_ns` [ns]."""
        self.count += 1
        self.times.append(t_ns)
        self.sizes.append(size)
        if kind:
            self.kinds.add(kind)
        if publisher:
            self.publishers.add(publisher)

    def figures(self) -> Figures:
        n = len(self.times)
        mean_size = sum(self.sizes) / n if n else 0.0
        if n < 2:
            return Figures(n, 0.0, None, None, None, 0.0, mean_size)
        periods = [(b - a) / 1e9 for a, b in zip(self.times, list(self.times)[1:],
                                                  strict=False)]
        span = (self.times[-1] - self.times[0]) / 1e9
        mean = span / len(periods)
        std = math.sqrt(sum((p - mean) ** 2 for p in periods) / len(periods))
        rate = len(periods) / span if span > 0 else math.inf
        later = sum(self.sizes) - self.sizes[0]  # what arrived after the first, over the span
        bw = later / span if span > 0 else math.inf
        return Figures(n, rate, min(periods), max(periods), std, bw, mean_size)


def human_bytes(n: float) -> str:
    """`n` bytes as B, kB, MB (powers of 1000, as ros2 topic bw prints them)."""
    for unit, scale in (("MB", 1e6), ("kB", 1e3)):
        if abs(n) >= scale:
            return f"{n / scale:.2f} {unit}"
    return f"{n:.0f} B"


def hz_line(name: str, f: Figures, bw: bool) -> str:
    """One key's figures as `teleo hz` prints them."""
    if f.messages < 2:
        return f"{name}: {f.messages} message(s) so far, no rate yet"
    line = (f"{name}: {f.rate:.2f} msg/s  period min {f.period_min:.4f} s  max "
            f"{f.period_max:.4f} s  std {f.period_std:.4f} s  window {f.messages}")
    if bw:
        line += f"  {human_bytes(f.bytes_per_s)}/s  mean {human_bytes(f.mean_size)}"
    return line


def list_table(meters: dict[str, Meter]) -> list[str]:
    """`teleo echo --list`: one row per key (sorted) with its kind, rate, mean size and
    publishers, under a header."""
    rows = [("KEY", "KIND", "RATE/s", "MEAN B", "PUBLISHERS")]
    for key in sorted(meters):
        m = meters[key]
        f = m.figures()
        rows.append((key, ",".join(sorted(m.kinds)) or "?", f"{f.rate:.1f}",
                     f"{f.mean_size:.0f}", ",".join(sorted(m.publishers)) or "?"))
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    return [f"{r[0]:<{widths[0]}}  {r[1]:<{widths[1]}}  {r[2]:>{widths[2]}}  "
            f"{r[3]:>{widths[3]}}  {r[4]}" for r in rows]
