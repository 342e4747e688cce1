"""The contract every domain meets, and the registry the world process picks a domain from.

A domain (urban driving, Blocks World, office delivery) is a simulation in HighwayEnv's
fixed-loop-plus-hooks shape: the world process owns the loop of one cycle (inject the events
due, publish the state, collect actions, apply them, step) and each domain fills in the hooks
below. Perception and rendering are pure functions of a snapshot dict, so an agent's
perception process and the tools need nothing but the snapshot and the domain's name, which
every snapshot carries under "domain".

    domain = get_domain(scenario.world_domain)
    world = domain.create(scenario.world, seed, ["ME"])      # raises ConfigError naming the key
    outcomes = world.apply_actions("ME", [["*gas", 30]])     # never raises
    world.step()
    snap = world.snapshot_dict()                              # plain data: msgpack/JSON-able
    percepts = domain.perceive(snap, "ME")                    # neutral percept lists

Restart (docs/faults.md): a world process that dies is started again and resumes at the cycle
it had reached, deterministically. It rebuilds the simulation from its last checkpoint and
replays the actions and events recorded since (world/resume.py), so a domain must be
deterministic given its seed, the actions and the events (the contract test checks it), and
should offer `checkpoint()` (Restartable) and `Domain.restore`, the exact inverse:

    blob = world.checkpoint()                  # bytes, before the next cycle's injections
    again = domain.restore(blob)               # continues exactly as `world` would

A domain without them still restarts, by replaying the whole run from cycle 0 (slower: its
restart time grows with the run's length).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

from bus.schema import FieldError, Plain, brief
from world.errors import ConfigError

Outcome = dict[str, Any]
"""{"action": [...], "status": "done" | "failed", "reason": str} (docs/architecture.md)."""

_EVENT_DATA = Plain(max_depth=8, top=None)
"""An event kept in its outcome: every world's events are flat maps (a size is a list in
one), and an outcome nested in a world state must stay within the bus's bounds (bus/fields.py:
16 levels for the state's events)."""


def event_problem(schema: Any, event: Any) -> str:
    """What ``schema`` (a domain's EVENTS) finds wrong with ``event``, or ""."""
    try:
        schema.check(event)
    except FieldError as exc:
        return str(exc)
    return ""


def event_outcome(event: Any, reason: str = "") -> dict[str, Any]:
    """An injected event's outcome, {"event", "status": "done"|"failed", "reason"} (failed
    when there is a ``reason``). It goes into the world state and the trace, so a refused
    event that is not plain data (bytes, NaN, nested too deep: docs/faults.md, "Hostile
    input") is kept as its shortened text."""
    try:
        _EVENT_DATA.check(event)
    except FieldError:
        event = brief(event, 200)
    return {"event": event, "status": "failed" if reason else "done", "reason": reason}


@runtime_checkable
class World(Protocol):
    """A running simulation of one domain. Every method is deterministic given the seed."""

    cycle: int

    def apply_actions(self, agent: str, actions: list[list[Any]]) -> list[Outcome]:
        """Apply one agent's actions of this cycle; one outcome per action. Never raises: an
        unknown agent or action gets a failed outcome naming it."""

    def safe_actions(self, agent: str) -> list[list[Any]]:
        """What an agent whose actions did not arrive gets this cycle (brake and hold; stop)."""

    def inject(self, event: dict[str, Any]) -> dict[str, Any]:
        """Apply a scenario event or fault: {"event", "status": "done"|"failed", "reason"}."""

    def step(self) -> None:
        """Advance one fixed dt [s]."""

    def snapshot_dict(self) -> dict[str, Any]:
        """The observable state of the current cycle as plain data, with at least "domain",
        "cycle", "time" [s] and "counters" ({agent: {name: int}})."""


@runtime_checkable
class Restartable(Protocol):
    """A World that can be saved between cycles and restored by its Domain.restore."""

    def checkpoint(self) -> bytes:
        """The whole state of the simulation as bytes (a pickle is fine: the file lives in
        the run folder, written and read by the same user)."""


@dataclass(frozen=True)
class Domain:
    """A domain's hooks. ``violations`` names the counters that are breaches of a law or a
    safety rule (a run's summary lists them); ``event_kinds`` the events ``inject`` knows;
    ``actions`` the action names ``apply_actions`` knows (a program sending another is
    refused by `teleo check` of a scenario: the world would fail it every cycle);
    ``check_event`` says what is wrong with an event's fields ("" when nothing: the kind's
    schema, before the world's own checks), so a scenario's [[events]] are checked before
    the run."""

    name: str
    summary: str
    create: Callable[[dict[str, Any], int, list[str]], World]
    perceive: Callable[[dict[str, Any], str], list[list[Any]]]
    render: Callable[[Sequence[dict[str, Any]], Path, str | None], int]
    check_config: Callable[[dict[str, Any], list[str]], None]
    violations: tuple[str, ...] = ()
    event_kinds: tuple[str, ...] = ()
    achievements: tuple[str, ...] = field(default=())  # counters of work done (deliveries)
    restore: Callable[[bytes], World] | None = None     # the inverse of World.checkpoint
    actions: tuple[str, ...] = ()
    check_event: Callable[[Any], str] | None = None


# name -> module whose DOMAIN attribute is the Domain (imported on first use, so a process
# that runs one domain never imports the others' physics).
_MODULES = {
    "driving": "world.driving",
    "blocks": "world.blocks",
    "office": "world.office",
    "pddl": "world.pddl",
}
DOMAINS: tuple[str, ...] = tuple(_MODULES)
DEFAULT_DOMAIN = "driving"


def get_domain(name: str) -> Domain:
    """The Domain called ``name``; raises ConfigError listing the known ones."""
    module = _MODULES.get(name)
    if module is None:
        raise ConfigError(f"[world] domain: unknown domain {name!r}; known: {', '.join(DOMAINS)}")
    return importlib.import_module(module).DOMAIN


def domain_of(snapshot: dict[str, Any]) -> Domain:
    """The Domain a snapshot dict belongs to (its "domain" key; driving if absent)."""
    return get_domain(str(snapshot.get("domain", DEFAULT_DOMAIN)))
