"""One cognitive cycle, written once (docs/bus.md, "The cycle"): the world
process (world/process.py, agents over the bus) and `teleo simulate` (tools/commands/simulate.py,
agents in the same process) both run it through a CycleRunner and differ only in their
`Agents`, the transport.

For cycle t: inject the events due (the scenario's scripted events of t, then whatever the
transport says arrived), take the snapshot of t, hand the agents the world state of t (the
moving part of the snapshot, each agent's action outcomes of t-1 and the memory it last sent),
take each agent's actions and memory back, apply the actions in agent order (the world's safe
action for an agent given the no-op), step the physics. The memory an agent sends with its
actions is kept and handed back in the next world state: that round trip is the only way an
agent's world model reaches its inference (docs/bus.md, "Agent memory"), in-process as on the
bus. What changed of it goes in the trace line. The core knows no transport (world/ touches
the bus only in world/process.py): a transport makes its message of a `CycleState` and answers
with anything shaped as a `Reply` (bus.cycle.CycleReport is one).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol

from world.domain import World, episode_over
from world.static import split
from world.trace import trace_line

__all__ = ["Agents", "CycleDone", "CycleRunner", "CycleState", "Reply"]


@dataclass(frozen=True)
class CycleState:
    """What the agents are handed at cycle `t` (the fields of the bus's WorldState): the
    moving part of the snapshot (world/static.py), each agent's action outcomes of t-1, the
    outcomes of the events injected at t, each agent's memory as it last sent it, and what
    changes at the start of t (world/changes.py)."""

    t: int
    snapshot: dict[str, Any]
    outcomes: dict[str, list]
    events: list[dict[str, Any]]
    memory: dict[str, dict[str, Any]] = field(default_factory=dict)
    control: dict[str, Any] = field(default_factory=dict)


class Reply(Protocol):
    """The agents' answer: each agent's actions (action lists), the memory each sent with
    them, and the agents given the no-op (none came in time: the world's safe action)."""

    actions: Mapping[str, Sequence]
    memory: Mapping[str, dict[str, Any]]
    noop: tuple[str, ...]


class Agents(Protocol):
    """The agents' side of a cycle: the transport. `act` gets the state of cycle `t` and the
    whole snapshot it was taken from (for work the transport does while the agents decide:
    the bus's record digest) and returns every agent's actions and memory of `t`."""

    def act(self, state: CycleState, snap: dict[str, Any]) -> Reply: ...


@dataclass(frozen=True)
class CycleDone:
    """What one cycle did: the snapshot of t (before its actions), the events injected, the
    actions applied per agent, the agents' report, the memories that changed, the world's
    own compute time [ms] and whether t was the episode's last state."""

    t: int
    snap: dict[str, Any]
    injected: list[dict[str, Any]]
    applied: dict[str, list[list[Any]]]
    report: Any   # the transport's Reply
    changed: dict[str, dict[str, Any]]
    world_ms: float
    over: bool

    def trace(self) -> str:
        """The cycle's trace line (world/trace.py)."""
        return trace_line(self.t, self.snap, self.applied, self.injected, self.changed)


class CycleRunner:
    """The world's side of every cycle of a run. `events`: the scenario's scripted events
    (each with `at_cycle` and `event`); `outcomes` and `memory`: each agent's, as the run
    left them (a resumed run), else none yet (empty)."""

    def __init__(self, sim: World, agents: Sequence[str], events: Iterable[Any],
                 outcomes: dict[str, list] | None = None,
                 memory: dict[str, dict[str, Any]] | None = None) -> None:
        self.sim, self.agents = sim, tuple(agents)
        self.scripted: dict[int, list[dict[str, Any]]] = {}
        for e in events:
            self.scripted.setdefault(e.at_cycle, []).append(e.event)
        self.outcomes: dict[str, list] = outcomes if outcomes is not None \
            else {a: [] for a in self.agents}
        self.memory: dict[str, dict[str, Any]] = memory if memory is not None \
            else {a: {} for a in self.agents}
        self.static = split(sim.snapshot_dict())[0]   # told once a run

    def cycle(self, t: int, agents: Agents,
              arrived: Callable[[World], list[dict[str, Any]]] | None = None,
              control: dict[str, Any] | None = None) -> CycleDone:
        """Run cycle `t` with `agents`; `arrived(sim)`: the outcomes of events the transport
        injects after the scripted ones (the bus's world/events); `control`: what changes
        at the start of t (world/changes.py), for the world state."""
        w0 = time.perf_counter()
        injected = [self.sim.inject(e) for e in self.scripted.get(t, [])]
        if arrived is not None:
            injected += arrived(self.sim)
        snap = self.sim.snapshot_dict()
        over = episode_over(self.sim)   # this state is the episode's last: the last cycle
        world_ms = (time.perf_counter() - w0) * 1e3
        state = CycleState(t, split(snap)[1], {a: self.outcomes.get(a, []) for a in self.agents},
                           injected, dict(self.memory), dict(control or {}))
        report = agents.act(state, snap)
        changed = {a: m for a, m in report.memory.items() if self.memory.get(a) != m}
        self.memory.update(changed)   # an agent given the no-op keeps its last memory
        w0 = time.perf_counter()
        applied = {a: self._actions_of(a, acts, report.noop)
                   for a, acts in report.actions.items()}
        self.outcomes = {a: self.sim.apply_actions(a, acts) for a, acts in applied.items()}
        self.sim.step()
        world_ms += (time.perf_counter() - w0) * 1e3
        return CycleDone(t, snap, injected, applied, report, changed, world_ms, over)

    def _actions_of(self, agent: str, actions: Sequence, noop: tuple[str, ...]
                    ) -> list[list[Any]]:
        """The agent's actions of this cycle, or the world's safe action when they did not
        arrive (a dead or late stage): an uncontrolled agent is stopped, never left on its
        last controls."""
        if agent in noop:
            return self.sim.safe_actions(agent)
        return [list(x) for x in actions]
