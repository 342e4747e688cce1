"""Message kinds on the bus (docs/architecture.md, bus section): frozen dataclasses, each
with an envelope. Payload data uses the neutral forms (plain lists and dicts, msgpack-able).

The kind name of each class is its `KIND` and is what the codec writes on the wire.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import ClassVar

SCHEMA_VERSION = 1
"""The bus protocol's major version, written as ``env.v`` in every message. A change that
only adds fields (readers ignore fields they do not know) keeps it; any other change raises
it, and a reader refuses a message of another major version (bus/codec.py; docs/bus.md,
"Envelope")."""

GOAL_OPS = ("post", "cancel", "priority", "list", "update")
"""Allowed `GoalRequest.op` values."""


@dataclass(frozen=True)
class Envelope:
    """Who sent what for which cycle.

    v: the protocol's major version (SCHEMA_VERSION); run: run id; cycle: cycle number
    (>= 0; -1 for messages outside the cycle, e.g. goal requests); sender: process name;
    sent_ns: wall clock at send [ns].
    """

    v: int
    run: str
    cycle: int
    sender: str
    sent_ns: int

    @classmethod
    def now(cls, run: str, cycle: int, sender: str) -> Envelope:
        """An envelope of the current schema version stamped with the current time."""
        return cls(SCHEMA_VERSION, run, cycle, sender, time.time_ns())


@dataclass(frozen=True)
class WorldState:
    """World state of a cycle, with each agent's action outcomes of the previous cycle and
    the memory each agent last sent with its actions (docs/bus.md, "Agent memory").
    ``control``: what changes at the start of this cycle ({} on every other cycle; docs/bus.md,
    "Changing a running launch"): {"programs": {agent: {"name", "text"}}, "set": [{"key",
    "value"}]}."""

    KIND: ClassVar[str] = "WorldState"
    env: Envelope
    snapshot: dict
    outcomes: dict  # agent -> list of outcome dicts {"action", "status", "reason"}
    events: list
    memory: dict = field(default_factory=dict)  # agent -> its memory map (as sent)
    control: dict = field(default_factory=dict)  # what changes at this cycle (below)


@dataclass(frozen=True)
class WorldStatic:
    """A world's static configuration (the snapshot keys its domain names in static_keys:
    driving's and the office's config, the blocks table), sent once per run on
    teleo/<run>/world/static rather than in every world state, and served there as a query
    (any WorldStatic asks; the reply is the world's): a reader puts it back into each world
    state (world/static.py). ``static`` is {} when there is none and in a request."""

    KIND: ClassVar[str] = "WorldStatic"
    env: Envelope
    domain: str
    static: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Percepts:
    """An agent's percepts of a cycle, with the outcomes of its actions of the previous
    cycle as the world reported them (SCS failure semantics and ROGUE's monitoring use them)."""

    KIND: ClassVar[str] = "Percepts"
    env: Envelope
    agent: str
    percepts: tuple  # tuple of percept lists, e.g. ["self", "ME", "speed", 20.0]
    outcomes: tuple = ()  # tuple of {"action": [...], "status": "done"|"failed", "reason": str}
    memory: dict = field(default_factory=dict)  # the agent's memory, as the world echoed it
    program: dict = field(default_factory=dict)  # {"name", "text"}: run it from this cycle


@dataclass(frozen=True)
class Beliefs:
    KIND: ClassVar[str] = "Beliefs"
    env: Envelope
    agent: str
    beliefs: tuple  # tuple of belief lists, e.g. ["at-street", "ME", "B"]
    swap: dict = field(default_factory=dict)  # a program swapped in: {"program", "ok", "reason"}


@dataclass(frozen=True)
class Actions:
    """Actions of one agent for one cycle; an empty tuple is the no-op. ``memory``: what the
    agent asks the world to keep and hand back with the next world state (its world-model
    facts, SCS threads and discount factors; docs/bus.md, "Agent memory")."""

    KIND: ClassVar[str] = "Actions"
    env: Envelope
    agent: str
    actions: tuple  # tuple of action lists, e.g. ["*gas", 6.25]
    memory: dict = field(default_factory=dict)  # {"model": [fact lists], "scs": {...}}


@dataclass(frozen=True)
class Intention:
    KIND: ClassVar[str] = "Intention"
    env: Envelope
    agent: str
    decision: dict  # the engine's Decision.to_dict()
    swap: dict = field(default_factory=dict)  # {"program", "ok", "reason", "dropped"}


@dataclass(frozen=True)
class GoalRequest:
    KIND: ClassVar[str] = "GoalRequest"
    env: Envelope
    op: str  # one of GOAL_OPS
    agent: str
    goal: str = ""
    priority: int = 0
    goal_id: str = ""
    force: bool = False  # rank above the program's goals or cancel an achieved goal all the same
    once: bool = False   # a post: dropped when achieved, not kept as a maintenance goal
    deadline: int = 0    # a post: failed unless achieved within this many cycles (0: none)


@dataclass(frozen=True)
class GoalReply:
    KIND: ClassVar[str] = "GoalReply"
    env: Envelope
    ok: bool
    reason: str
    goals: tuple = ()  # tuple of goal dicts


@dataclass(frozen=True)
class GoalList:
    """An agent's goal list for one cycle (the executive's goal input of that cycle)."""

    KIND: ClassVar[str] = "GoalList"
    env: Envelope
    agent: str
    goals: tuple = ()  # tuple of {"id", "goal", "priority", "status"} dicts


@dataclass(frozen=True)
class ProcessStats:
    """Per-cycle figures of one process, for the clock (which stage is late) and the inspector.

    compute_ms: time spent computing this cycle [ms]; late: cycles this process has
    skipped so far because a newer cycle had already arrived (it fell behind) [count].
    """

    KIND: ClassVar[str] = "ProcessStats"
    env: Envelope
    process: str
    compute_ms: float
    late: int


@dataclass(frozen=True)
class WorldEvent:
    KIND: ClassVar[str] = "WorldEvent"
    env: Envelope
    event: dict


@dataclass(frozen=True)
class EventReply:
    """The world's verdict on an event asked for on teleo/<run>/world/events (a query, as
    `teleo event` sends it): ok when applied, else the world's reason; env.cycle is the cycle
    at whose start it was applied; outcome is what the trace records,
    {"event", "status": "done"|"failed", "reason"}."""

    KIND: ClassVar[str] = "EventReply"
    env: Envelope
    ok: bool
    reason: str
    outcome: dict = field(default_factory=dict)


Message = (
    WorldState | WorldStatic | Percepts | Beliefs | Actions | Intention | GoalRequest
    | GoalReply | GoalList | ProcessStats | WorldEvent | EventReply
)

MESSAGE_TYPES: dict[str, type] = {
    cls.KIND: cls
    for cls in (WorldState, WorldStatic, Percepts, Beliefs, Actions, Intention, GoalRequest,
                GoalReply, GoalList, ProcessStats, WorldEvent, EventReply)
}
