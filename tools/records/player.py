"""How `teleo replay` plays a record, as `ros2 bag play` does: cycle by cycle, paced by the
record's world time at `--rate`, from `--start CYCLE`, again and again with `--loop`, and on a
terminal with keys: space pauses and resumes, `s` or the right arrow plays one cycle while
paused (`--paused` starts so). Without a terminal there are no keys.

`cycles_of` groups a record's messages by cycle; `Player` plays the groups through a `send`
function, asking a key source between them; `TerminalKeys` reads keys from a terminal in
cbreak mode (Ctrl-C still interrupts) and puts the terminal back as it was.
"""

from __future__ import annotations

import os
import select
import sys
import termios
import threading
import time
import tty
from collections.abc import Callable, Iterable
from dataclasses import dataclass

PAUSE, STEP = "pause", "step"
KEYS = {b" ": PAUSE, b"s": STEP, b"S": STEP, b"\x1b[C": STEP}
"""Key presses -> what they do (the right arrow is ESC [ C)."""
LOOK_S = 0.05  # [s] between looks at the keys while waiting


@dataclass(frozen=True)
class CycleGroup:
    """The messages of one cycle, in the record's order, with the cycle's world time [ns]."""

    cycle: int
    world_ns: int
    items: tuple[tuple[str, bytes], ...]


def cycles_of(items: Iterable[tuple[str, bytes, int]], times: dict[int, int]) -> list[CycleGroup]:
    """(key, payload, cycle) in record order -> one group per run of equal cycles, each with
    the world time of its cycle (`times`: cycle -> [ns]; the last known one for a cycle
    without a world state, such as the messages outside any cycle; the first known one for
    those before any: a record started mid-run whose first cycle lacks its state would
    otherwise be paced from world time 0, hundreds of seconds before its next cycle)."""
    groups: list[CycleGroup] = []
    current: list[tuple[str, bytes]] = []
    cycle: int | None = None
    last_ns = times[min(times)] if times else 0
    for key, payload, c in items:
        if c != cycle and current:
            groups.append(CycleGroup(cycle, last_ns, tuple(current)))
            current = []
        cycle = c
        last_ns = times.get(c, last_ns)
        current.append((key, payload))
    if current:
        groups.append(CycleGroup(cycle, last_ns, tuple(current)))
    return groups


def from_cycle(groups: list[CycleGroup], start: int) -> list[CycleGroup]:
    """The groups from cycle `start` on; raises ValueError naming the record's cycles when
    it holds none that late."""
    cycles = [g.cycle for g in groups if g.cycle >= 0]
    if not cycles or start > max(cycles):
        held = f"cycles {min(cycles)}..{max(cycles)}" if cycles else "no cycle"
        raise ValueError(f"the record holds {held}, got {start}")
    first = next(i for i, g in enumerate(groups) if g.cycle >= start)
    return groups[first:]


class NoKeys:
    """The key source without a terminal: none ever pressed; waits on `stop`."""

    def __init__(self, stop: threading.Event) -> None:
        self.stop = stop

    def poll(self, timeout: float) -> str | None:
        self.stop.wait(max(0.0, timeout))
        return None


class TerminalKeys(NoKeys):
    """Keys from the terminal on `fd` (cbreak mode while in use: a key is read as it is
    pressed, unechoed; Ctrl-C still sends SIGINT)."""

    def __init__(self, stop: threading.Event, fd: int) -> None:
        super().__init__(stop)
        self.fd = fd
        self._saved = termios.tcgetattr(fd)

    def __enter__(self) -> TerminalKeys:
        tty.setcbreak(self.fd)
        return self

    def __exit__(self, *_exc: object) -> None:
        termios.tcsetattr(self.fd, termios.TCSADRAIN, self._saved)

    def poll(self, timeout: float) -> str | None:
        end = time.monotonic() + max(0.0, timeout)
        while not self.stop.is_set():
            ready, _, _ = select.select([self.fd], [], [], min(LOOK_S, max(0.0, end -
                                                                          time.monotonic())))
            if ready:
                data = os.read(self.fd, 8)
                return KEYS.get(data, KEYS.get(data[:1]))
            if time.monotonic() >= end:
                return None
        return None


def terminal_keys(stop: threading.Event) -> TerminalKeys | None:
    """Keys from stdin when it is a terminal, else None."""
    try:
        fd = sys.stdin.fileno()
    except (AttributeError, OSError, ValueError):
        return None
    return TerminalKeys(stop, fd) if os.isatty(fd) else None


class Player:
    """Plays cycle groups through `send(key, payload)`, paced by world time at `rate` (0: as
    fast as possible), paused at first with `paused`, from the start again with `loop`;
    `say(text)` tells of pauses, steps and loops. Stops when `stop` is set."""

    def __init__(self, groups: list[CycleGroup], send: Callable[[str, bytes], None],
                 rate: float, stop: threading.Event, keys: NoKeys, say: Callable[[str], None],
                 paused: bool = False, loop: bool = False) -> None:
        self.groups, self.send, self.rate = groups, send, rate
        self.stop, self.keys, self.say = stop, keys, say
        self.paused, self.loop = paused, loop
        self.sent = 0
        self.played_cycles = 0

    def play(self) -> int:
        """Play until the end (or forever with `loop`, until stopped); the messages sent."""
        if not self.groups:
            return 0
        if self.paused:
            self._said_paused(self.groups[0])
        while not self.stop.is_set():
            self._pass()
            if not self.loop or self.stop.is_set():
                break
            self.say(f"looping: cycle {self.groups[0].cycle} again")
        return self.sent

    def _pass(self) -> None:
        """One pass over the groups."""
        base, anchor = time.monotonic(), self.groups[0].world_ns
        i = 0
        while i < len(self.groups) and not self.stop.is_set():
            group = self.groups[i]
            if self.paused:
                key = self.keys.poll(LOOK_S * 2)
                if key == PAUSE:
                    self.paused = False
                    base, anchor = time.monotonic(), group.world_ns
                    self.say(f"playing from cycle {group.cycle}")
                elif key == STEP:
                    self._send(group)
                    i += 1
                    self.say(f"stepped: cycle {group.cycle} sent")
                continue
            due = base + ((group.world_ns - anchor) / 1e9 / self.rate if self.rate > 0 else 0)
            if self._wait(due):
                self.paused = True
                self._said_paused(group)
                continue
            self._send(group)
            i += 1

    def _wait(self, due: float) -> bool:
        """Wait until `due` [monotonic s] reading keys; whether a pause was asked for."""
        while not self.stop.is_set():
            left = due - time.monotonic()
            key = self.keys.poll(min(LOOK_S, left)) if left > 0 else self.keys.poll(0)
            if key == PAUSE:
                return True
            if left <= 0:
                return False
        return False

    def _send(self, group: CycleGroup) -> None:
        for key, payload in group.items:
            self.send(key, payload)
            self.sent += 1
        self.played_cycles += 1

    def _said_paused(self, group: CycleGroup) -> None:
        self.say(f"paused before cycle {group.cycle} (space: play, s or right arrow: one "
                 "cycle)")
