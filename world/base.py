"""What every world shares, so that a world (teleo's three, or a plug-in's) writes only what is
its own: HighwayEnv's AbstractEnv shape, with the loop itself in world/process.py.

BaseWorld   the World protocol's common half (world/domain.py): the guards of apply_actions
            (not a list; an unknown agent gets a failed outcome per action), inject (apply,
            report the injected event in the next snapshot, log a refusal) and snapshot_dict;
            a world fills in `actors`, `act`, `apply_event` and `snapshot`.
record      a frozen dataclass from a plain dict, refusing unknown keys (WorldError)
rebuild     a snapshot's `from_dict`: check against its schema, then build, WorldError on both
config_reader  the config a snapshot carries, checked as plain data, read once per distinct
            config (world/parsed.py)
COMMON      the snapshot fields every world has (counters, events), for its SNAPSHOT schema
deg, r3     an angle [rad] as [deg] in (-180, 180]; a number as perception shows it (3 places)
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import fields
from functools import cache
from typing import Any, TypeVar

from bus.schema import FieldError, Int, ListOf, MapOf, Plain
from world.angles import wrap
from world.errors import WorldError
from world.parsed import parsed_by_value

T = TypeVar("T")
Outcome = dict[str, Any]

COMMON: dict[str, Any] = {"counters": MapOf(MapOf(Int())), "events": ListOf(Plain(16))}
"""Every world's snapshot has per-agent counters ({agent: {name: int}}) and the events of the
step into it (flat maps)."""

MALFORMED = (KeyError, TypeError, ValueError, AttributeError)
"""What building a snapshot from a dict the schema let through can still raise."""


def deg(rad: float) -> float:
    """An angle [rad] as [deg], folded into (-180, 180]."""
    return wrap(math.degrees(rad))


def r3(value: float) -> float:
    """A number as perception shows it: 3 decimal places, and never -0.0."""
    return round(float(value), 3) + 0.0


@cache
def _names(kind: type) -> frozenset[str]:
    return frozenset(f.name for f in fields(kind))


def record(kind: type[T], d: dict[str, Any]) -> T:
    """``kind(**d)`` for a frozen dataclass; raises WorldError naming unknown keys."""
    names = _names(kind)
    if not names.issuperset(d):
        raise WorldError(f"{kind.__name__}: unknown keys {sorted(set(d) - names)}")
    return kind(**d)


_passed: dict[int, Any] = {}
"""id(schema) -> the last dict that passed it, kept (so its id is its own): several agents
perceiving one snapshot in one process (a shared process, `teleo simulate`) check it once.
Snapshot dicts are not changed once made (they are read from the bus, or a world's copy)."""


def rebuild(cls: type, schema: Any, d: Any, build: Callable[[], T]) -> T:
    """A snapshot's ``from_dict``: ``d`` checked against ``schema`` (WorldError "snapshot:
    <field>: ..."; not again for the dict that passed last), then ``build()``; a malformed
    dict the schema let through is a WorldError naming the class."""
    if _passed.get(id(schema)) is not d:
        try:
            schema.check(d)
        except FieldError as exc:
            raise WorldError(f"snapshot: {exc}") from None
        _passed[id(schema)] = d
    try:
        return build()
    except MALFORMED as exc:
        raise WorldError(f"{cls.__name__}.from_dict: malformed snapshot dict ({exc!r})") \
            from exc


def config_reader(load: Callable[[Any], T]) -> Callable[[Any], T]:
    """The reader of the config a snapshot carries: plain data (WorldError "snapshot: config:
    ..."), then ``load`` (ConfigError naming the key); cached by value, since every snapshot
    of a run carries the same config."""
    data = Plain(16)

    def checked(d: Any) -> T:
        try:
            data.check(d)
        except FieldError as exc:
            raise WorldError(f"snapshot: config: {exc}") from None
        return load(d)

    return parsed_by_value(checked)


def _action_list(a: Any) -> list[Any]:
    return list(a) if isinstance(a, list | tuple) else [repr(a)]


class BaseWorld:
    """The common half of a World. A subclass sets ``cycle`` and ``_incoming`` (the events of
    the coming step, reported in the next snapshot) and fills in the four hooks below."""

    cycle: int
    _incoming: list[dict[str, Any]]

    # -- the hooks a world fills in ---------------------------------------------------------
    def actors(self) -> Mapping[str, Any]:
        """What each agent acts through (a car, a gripper, a robot), by agent id."""
        raise NotImplementedError

    def act(self, actor: Any, actions: Iterable[Any]) -> list[Outcome]:
        """Apply an agent's actions of this cycle in order through its actor; outcomes."""
        raise NotImplementedError

    def apply_event(self, event: dict[str, Any]) -> Outcome:
        """Apply a scenario event: {"event", "status", "reason"}; never raises."""
        raise NotImplementedError

    def snapshot(self) -> Any:
        """The frozen state of the current cycle (with ``to_dict``)."""
        raise NotImplementedError

    # -- the World protocol ------------------------------------------------------------------
    def apply_actions(self, agent: str, actions: list[list[Any]]) -> list[Outcome]:
        """Apply an agent's actions of this cycle; one outcome per action, never raises: a
        value that is not a list, or an agent of no actor, gets failed outcomes naming it."""
        if not isinstance(actions, list | tuple):
            return [{"action": [repr(actions)], "status": "failed",
                     "reason": f"{agent}: expected a list of actions, got {actions!r:.80}"}]
        actors = self.actors()
        actor = actors.get(agent)
        if actor is None:
            reason = f"unknown agent {agent!r}; agents: {sorted(actors)}"
            return [{"action": _action_list(a), "status": "failed", "reason": reason}
                    for a in actions]
        return self.act(actor, actions)

    def inject(self, event: dict[str, Any]) -> Outcome:
        """Apply a scenario event or fault; a done one is reported in the next snapshot's
        events ({"kind": "injected", "cycle", "event"}), a refused one logged. Never raises."""
        outcome = self.apply_event(event)
        if outcome["status"] == "done":
            self._incoming.append({"kind": "injected", "cycle": self.cycle, "event": dict(event)})
        else:
            logging.getLogger(type(self).__module__).info("cycle %d: %s", self.cycle,
                                                          outcome["reason"])
        return outcome

    def snapshot_dict(self) -> dict[str, Any]:
        """``snapshot()`` as plain data (the World protocol, world/domain.py)."""
        return self.snapshot().to_dict()
