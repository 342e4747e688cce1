"""Pure cycle bookkeeping (no zenoh): the stage-side join of inputs by cycle number and the
clock-side record of one cycle. Unit-tested without a bus (tests/bus/test_cycle.py)."""

from __future__ import annotations

import enum
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from bus.messages import Actions, Message
from bus.stats import figures_of

MAX_PENDING = 64
"""Incomplete cycles a stage keeps at most (older ones are dropped as stale)."""


class CycleMode(enum.StrEnum):
    LOCKSTEP = "lockstep"  # the world waits for every live agent's actions of t
    REALTIME = "realtime"  # fixed rate; missing actions default to the no-op


class DeadPolicy(enum.StrEnum):
    CONTINUE = "continue"  # count the dead stage, give its agent no-op actions, go on
    STOP = "stop"          # raise ClockStopped


@dataclass(frozen=True)
class Joined:
    """A complete set of inputs of one cycle. `repeat`: this cycle was already handled, so
    the stage re-emits its cached outputs instead of computing again."""

    cycle: int
    inputs: dict[str, Message]
    repeat: bool


class Joiner:
    """Joins the messages of several input keys by cycle number; never mixes cycles.

    `add` returns a Joined when the last missing input of a cycle arrives; messages of
    cycles older than the last handled one are counted in `stale` and dropped.
    """

    def __init__(self, inputs: Sequence[str]) -> None:
        if not inputs:
            raise ValueError("a stage needs at least one input key")
        self.inputs = tuple(inputs)
        self.last_done: int | None = None
        self.stale = 0
        self._pending: dict[int, dict[str, Message]] = {}

    def add(self, key: str, msg: Message) -> Joined | None:
        if key not in self.inputs:
            return None
        cycle = msg.env.cycle
        if self.last_done is not None and cycle < self.last_done:
            self.stale += 1
            return None
        slot = self._pending.setdefault(cycle, {})
        slot[key] = msg
        if len(slot) < len(self.inputs):
            self._trim()
            return None
        del self._pending[cycle]
        older = [c for c in self._pending if c < cycle]
        for c in older:
            del self._pending[c]
        self.stale += len(older)
        return Joined(cycle, slot, repeat=cycle == self.last_done)

    def pending_before(self, cycle: int) -> bool:
        """Whether an incomplete cycle older than `cycle` is still kept (it may complete)."""
        return any(c < cycle for c in self._pending)

    def done(self, cycle: int) -> None:
        """Mark `cycle` handled: later copies of it are repeats, older cycles are stale."""
        self.last_done = cycle if self.last_done is None else max(self.last_done, cycle)

    def _trim(self) -> None:
        while len(self._pending) > MAX_PENDING:
            del self._pending[min(self._pending)]
            self.stale += 1


def pick(batch: Sequence[Joined | None]) -> tuple[Joined | None, int]:
    """From the joins completed in one drain of the inbox, the one to act on (the newest
    cycle) and how many newer-than-handled cycles are skipped because of it."""
    ready = [j for j in batch if j is not None]
    if not ready:
        return None, 0
    best = max(ready, key=lambda j: j.cycle)
    skipped = len({j.cycle for j in ready if not j.repeat and j.cycle < best.cycle})
    return best, skipped


@dataclass
class CycleBook:
    """What the clock has heard for one cycle: each agent's actions and each stage's stats."""

    cycle: int
    agents: frozenset[str]
    actions: dict[str, tuple] = field(default_factory=dict)
    memory: dict[str, dict] = field(default_factory=dict)
    stage_ms: dict[str, float] = field(default_factory=dict)

    def record(self, msg: Message, last_seen: dict[str, int]) -> None:
        """Note `msg`; the stats it is or carries (bus/stats.py: a ProcessStats, an agent's
        Actions with its pipeline's), of any cycle, also update `last_seen[process]`."""
        cycle = msg.env.cycle
        for process, ms, _ in figures_of(msg):
            last_seen[process] = max(last_seen.get(process, -1), cycle)
            if cycle == self.cycle:
                self.stage_ms[process] = ms
        if isinstance(msg, Actions) and cycle == self.cycle and msg.agent in self.agents:
            self.actions.setdefault(msg.agent, msg.actions)
            self.memory.setdefault(msg.agent, msg.memory)

    def has(self, agent: str) -> bool:
        return agent in self.actions


def culprit(pipeline: Sequence[str], last_seen: Mapping[str, int], cycle: int) -> str:
    """The stage holding an agent's cycle up: the first, in pipeline order, that has not
    reported stats for `cycle` (the last stage if all did but no actions came). A stage's
    stats of a cycle reach the clock with the agent's Actions or, once the stage has been
    idle `Stage.quiet_s` after it, alone (bus/stage.py)."""
    for process in pipeline:
        if last_seen.get(process, -1) < cycle:
            return process
    return pipeline[-1]


@dataclass(frozen=True)
class CycleReport:
    """Outcome of one cycle on the clock side.

    actions: agent -> tuple of action lists (no-op `()` for agents in `noop`);
    late: stages that missed the per-cycle deadline (the first stuck stage of each
    agent); dead: stages whose liveliness token was gone; noop: agents given the no-op;
    republished: how many times state t was re-sent for a restarted stage;
    elapsed_ms: publish to return [ms]; stage_ms: each stage's compute time this cycle [ms];
    stalled: the stages the clock was still waiting for when the cycle passed the stall
    threshold (a lockstep cycle that waited, but whose actions did come);
    memory: agent -> the memory sent with its actions (absent for agents given the no-op).
    """

    cycle: int
    actions: dict[str, tuple]
    late: tuple[str, ...] = ()
    dead: tuple[str, ...] = ()
    noop: tuple[str, ...] = ()
    republished: int = 0
    elapsed_ms: float = 0.0
    stage_ms: dict[str, float] = field(default_factory=dict)
    stalled: tuple[str, ...] = ()
    memory: dict[str, dict] = field(default_factory=dict)

    @property
    def clean(self) -> bool:
        """Every agent acted in time and nothing was late or dead."""
        return not (self.late or self.dead or self.noop)
