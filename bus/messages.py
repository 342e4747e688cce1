"""Message kinds on the bus (docs/architecture.md, bus section; docs/bus.md, "Declaring a
message kind"): each declared once, here, as a frozen dataclass with an envelope, each field's
spec (bus/fields.py, bus/schema) in its metadata and the kind's keys, packed field and derived
record fields as class attributes (bus/kinds.py). Payload data uses the neutral forms (plain
lists and dicts, msgpack-able).

The kind name of each class is its `KIND` and is what the codec writes on the wire. A field
whose inside is another package's (a snapshot is its world's, a memory's SCS state the
engine's, an intention the engine's Decision) is checked here as plain data only, and by its
owner when read (bus/fields.py).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from bus.fields import (
    GOAL_ENTRY,
    MAP,
    MEMORY,
    MEMORY_DEPTH,
    NAME,
    OUTCOME,
    OUTCOMES,
    PROGRAM,
    STATS,
    SWAP,
    TEXT,
    All,
    Rows,
    Tuple,
)
from bus.kinds import MESSAGE_TYPES, Derived, MessageKind, message, spec
from bus.schema import Bool, Int, ListOf, MapOf, Num, OneOf, Plain

__all__ = ["GOAL_OPS", "MESSAGE_TYPES", "SCHEMA_VERSION", "Actions", "Beliefs", "Envelope",
           "EventReply", "GoalList", "GoalReply", "GoalRequest", "Intention", "Message",
           "Percepts", "ProcessStats", "WorldEvent", "WorldState", "WorldStatic"]

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


def self_attrs(body: dict) -> dict[str, Any]:
    """The attributes of a Percepts wire map's own ``(self AGENT ...)`` percept as an object
    ({} when there is none): a record's derived ``self``, so a plot can address
    ``.self.speed``."""
    agent, percepts = body.get("agent"), body.get("percepts")
    for p in percepts if isinstance(percepts, list) else ():
        if isinstance(p, list) and len(p) >= 2 and p[0] == "self" and p[1] == agent:
            return {str(p[i]): p[i + 1] for i in range(2, len(p) - 1, 2)}
    return {}


@message
class WorldState(MessageKind):
    """World state of a cycle, with each agent's action outcomes of the previous cycle and
    the memory each agent last sent with its actions (docs/bus.md, "Agent memory").
    ``control``: what changes at the start of this cycle ({} on every other cycle; docs/bus.md,
    "Changing a running launch"): {"programs": {agent: {"name", "text"}}, "set": [{"key",
    "value"}]}. The snapshot is its world's to check (the domain's SNAPSHOT, in perception: the
    only process that reads it), and each agent's memory in it is checked as a memory by that
    agent's perception, which forwards it (agents/processes/perception.py)."""

    KIND = "WorldState"
    KEYS = ("world/state",)
    env: Envelope
    snapshot: dict = spec(MAP)
    outcomes: dict = spec(All(Plain(16), MapOf(ListOf(OUTCOME))))  # agent -> outcome dicts
    events: list = spec(Plain(16, top=list))
    memory: dict = spec(All(Plain(MEMORY_DEPTH + 1), MapOf(MAP)), default_factory=dict)
    control: dict = spec(Plain(8), default_factory=dict)  # what changes at this cycle


@message
class WorldStatic(MessageKind):
    """A world's static configuration (the snapshot keys its domain names in static_keys:
    driving's and the office's config, the blocks table), sent once per run on
    teleo/<run>/world/static rather than in every world state, and served there as a query
    (any WorldStatic asks; the reply is the world's): a reader puts it back into each world
    state (world/static.py). ``static`` is {} when there is none and in a request."""

    KIND = "WorldStatic"
    KEYS = ("world/static",)
    env: Envelope
    domain: str = spec(NAME)
    static: dict = spec(Plain(16), default_factory=dict)


@message
class Percepts(MessageKind):
    """An agent's percepts of a cycle, with the outcomes of its actions of the previous
    cycle as the world reported them (SCS failure semantics and ROGUE's monitoring use them)."""

    KIND = "Percepts"
    KEYS = ("agent/*/percepts",)
    PACKED = "percepts"
    DERIVED = {"self": Derived(self_attrs, {
        "type": "object", "description": "derived: the agent's own self percept"})}
    env: Envelope
    agent: str = spec(NAME)
    percepts: tuple = spec(Rows())  # percept lists, e.g. ["self", "ME", "speed", 20.0]
    outcomes: tuple = spec(Tuple(OUTCOMES), default=())  # {"action", "status", "reason"}
    memory: dict = spec(MEMORY, default_factory=dict)  # the agent's memory, as echoed
    program: dict = spec(All(Plain(4), PROGRAM), default_factory=dict)  # {"name", "text"}
    stats: dict = spec(STATS, default_factory=dict)  # stage stats carried (bus/stats.py)


@message
class Beliefs(MessageKind):
    KIND = "Beliefs"
    KEYS = ("agent/*/beliefs",)
    PACKED = "beliefs"
    env: Envelope
    agent: str = spec(NAME)
    beliefs: tuple = spec(Rows())  # belief lists, e.g. ["at-street", "ME", "B"]
    swap: dict = spec(All(Plain(4), SWAP), default_factory=dict)  # a program swapped in
    stats: dict = spec(STATS, default_factory=dict)  # stage stats carried (bus/stats.py)


@message
class Actions(MessageKind):
    """Actions of one agent for one cycle; an empty tuple is the no-op. ``memory``: what the
    agent asks the world to keep and hand back with the next world state (its world-model
    facts, SCS threads and discount factors; docs/bus.md, "Agent memory")."""

    KIND = "Actions"
    KEYS = ("agent/*/actions",)
    env: Envelope
    agent: str = spec(NAME)
    actions: tuple = spec(Rows())  # action lists, e.g. ["*gas", 6.25]
    memory: dict = spec(MEMORY, default_factory=dict)  # {"model": [fact lists], "scs": {}}
    stats: dict = spec(STATS, default_factory=dict)  # stage stats carried (bus/stats.py)


@message
class Intention(MessageKind):
    KIND = "Intention"
    KEYS = ("agent/*/intention",)
    env: Envelope
    agent: str = spec(NAME)
    decision: dict = spec(Plain(MEMORY_DEPTH))  # the engine's Decision.to_dict()
    swap: dict = spec(All(Plain(4), SWAP), default_factory=dict)  # {"program", "ok", ...}


@message
class GoalRequest(MessageKind):
    KIND = "GoalRequest"
    KEYS = ("agent/*/goals",)
    env: Envelope
    op: str = spec(OneOf(GOAL_OPS, what="a goal operation"))
    agent: str = spec(TEXT)
    goal: str = spec(TEXT, default="")
    priority: int = spec(Int(), default=0)
    goal_id: str = spec(TEXT, default="")
    # rank above the program's goals or cancel an achieved goal all the same
    force: bool = spec(Bool(), default=False)
    once: bool = spec(Bool(), default=False)  # a post: dropped when achieved
    deadline: int = spec(Int(0), default=0)  # a post: failed unless achieved by then (0: none)


@message
class GoalReply(MessageKind):
    KIND = "GoalReply"
    KEYS = ("agent/*/goals",)
    env: Envelope
    ok: bool = spec(Bool())
    reason: str = spec(TEXT)
    goals: tuple = spec(Tuple(ListOf(Plain(8))), default=())  # goal dicts


@message
class GoalList(MessageKind):
    """An agent's goal list for one cycle (the executive's goal input of that cycle), with
    the goal-entry process's stats of that cycle (bus/stats.py; absent in older records)."""

    KIND = "GoalList"
    KEYS = ("agent/*/goal-list",)
    env: Envelope
    agent: str = spec(NAME)
    goals: tuple = spec(Tuple(ListOf(GOAL_ENTRY)), default=())  # {"id", "goal", ...} dicts
    stats: dict = spec(STATS, default_factory=dict)  # the goal entry's stats (bus/stats.py)


@message
class ProcessStats(MessageKind):
    """Per-cycle figures of one process, for the clock (which stage is late) and the inspector.
    A stage carries them in its output instead (the ``stats`` field of Percepts, Beliefs,
    Actions and GoalList; bus/stats.py) and sends them alone only when it has no such output
    or has been idle a while after a cycle (docs/bus.md, "Stage stats"); the world and the
    recorder send them alone.

    compute_ms: time spent computing this cycle [ms]; late: cycles this process has
    skipped so far because a newer cycle had already arrived (it fell behind) [count].
    """

    KIND = "ProcessStats"
    KEYS = ("stats/*",)
    env: Envelope
    process: str = spec(NAME)
    compute_ms: float = spec(Num(0.0, as_float=True))
    late: int = spec(Int(0))


@message
class WorldEvent(MessageKind):
    KIND = "WorldEvent"
    KEYS = ("world/events", "world/control")
    env: Envelope
    event: dict = spec(Plain(16))


@message
class EventReply(MessageKind):
    """The world's verdict on an event asked for on teleo/<run>/world/events (a query, as
    `teleo event` sends it): ok when applied, else the world's reason; env.cycle is the cycle
    at whose start it was applied; outcome is what the trace records,
    {"event", "status": "done"|"failed", "reason"}."""

    KIND = "EventReply"
    KEYS = ("world/events", "world/control")
    env: Envelope
    ok: bool = spec(Bool())
    reason: str = spec(TEXT)
    outcome: dict = spec(Plain(16), default_factory=dict)


Message = (
    WorldState | WorldStatic | Percepts | Beliefs | Actions | Intention | GoalRequest
    | GoalReply | GoalList | ProcessStats | WorldEvent | EventReply
)
"""The kinds declared here (a kind declared elsewhere with `message` is a bus message too)."""
