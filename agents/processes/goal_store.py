"""The goal-entry process's memory: user goals with their statuses, saved as JSON.

Pure: a GoalStore is a frozen value and every operation returns a new one; `save` and `load`
are the only I/O. ROGUE (seed 003) takes requests asynchronously with priorities and keeps
each task's state through suspension and resumption; here the executive reports each goal's
status in its intention and the store mirrors it. The goal-entry process saves the store
after every change, so a restart of any process loses no goal.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from enum import StrEnum
from pathlib import Path
from typing import Any

STORE_VERSION = 1


class GoalState(StrEnum):
    """A user goal's status as the goal-entry process reports it."""

    PENDING = "pending"
    ACTIVE = "active"
    SUSPENDED = "suspended"
    IMPASSE = "impasse"
    ACHIEVED = "achieved"
    FAILED = "failed"
    CANCELLED = "cancelled"


# The engine's GoalStatus (docs/architecture.md) -> the user's status, told as it is: an
# impasse (no executable skill path; the problem solver may be working on it) is reported as
# such, with the engine's note, and a failed goal as failed, with the reason.
_FROM_ENGINE = {
    "satisfied": GoalState.ACHIEVED,
    "active": GoalState.ACTIVE,
    "suspended": GoalState.SUSPENDED,
    "impasse": GoalState.IMPASSE,
    "pending": GoalState.PENDING,
    "failed": GoalState.FAILED,
}
# Goals in these states are no longer sent to the executive.
_WITHDRAWN = frozenset({GoalState.CANCELLED, GoalState.FAILED})


class GoalStoreError(Exception):
    """A request the store refuses; the message says which goal and why."""


# validate(agent, goal_text, priority) -> "" if the agent's program accepts the goal, else why not.
Validator = Callable[[str, str, int], str]


@dataclass(frozen=True)
class GoalRecord:
    """One user goal. Cycles are world cycles; priority: lower is more important."""

    id: str
    agent: str
    goal: str
    priority: int
    status: GoalState = GoalState.PENDING
    posted_cycle: int = 0
    updated_cycle: int = 0
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"id": self.id, "agent": self.agent, "goal": self.goal, "priority": self.priority,
                "status": self.status.value, "posted_cycle": self.posted_cycle,
                "updated_cycle": self.updated_cycle, "note": self.note}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> GoalRecord:
        return cls(d["id"], d["agent"], d["goal"], int(d["priority"]), GoalState(d["status"]),
                   int(d.get("posted_cycle", 0)), int(d.get("updated_cycle", 0)), d.get("note", ""))

    def brief(self) -> dict[str, Any]:
        """The GoalList entry form: {id, goal, priority, status} (docs/architecture.md)."""
        return {"id": self.id, "goal": self.goal, "priority": self.priority,
                "status": self.status.value}


@dataclass(frozen=True)
class GoalStore:
    """All user goals of a run, in posting order, with the bookkeeping a restart needs."""

    goals: tuple[GoalRecord, ...] = ()
    next_id: int = 1
    scripted_done: frozenset[int] = field(default_factory=frozenset)

    def get(self, goal_id: str) -> GoalRecord:
        for record in self.goals:
            if record.id == goal_id:
                return record
        raise GoalStoreError(f"no goal {goal_id!r} (known: {[g.id for g in self.goals]})")

    def for_agent(self, agent: str | None = None) -> tuple[GoalRecord, ...]:
        return tuple(g for g in self.goals if agent is None or g.agent == agent)

    def post(self, agent: str, goal: str, priority: int, cycle: int,
             validate: Validator) -> tuple[GoalStore, GoalRecord]:
        """Add a goal after the agent's program accepted it; raises GoalStoreError if refused."""
        text = " ".join(goal.split())
        if priority < 1:
            raise GoalStoreError(f"{text}: priority must be >= 1, got {priority}")
        for other in self.for_agent(agent):
            if other.goal == text and other.status not in _WITHDRAWN | {GoalState.ACHIEVED}:
                raise GoalStoreError(f"{text}: already posted for {agent} as {other.id}")
        reason = validate(agent, text, priority)
        if reason:
            raise GoalStoreError(f"{text}: refused for {agent}: {reason}")
        record = GoalRecord(f"g{self.next_id}", agent, text, priority, GoalState.PENDING,
                            cycle, cycle)
        return replace(self, goals=self.goals + (record,), next_id=self.next_id + 1), record

    def cancel(self, goal_id: str, cycle: int) -> GoalStore:
        """Withdraw a goal; the executive drops it from the next goal list it receives."""
        record = self.get(goal_id)
        if record.status is GoalState.CANCELLED:
            raise GoalStoreError(f"{goal_id}: already cancelled")
        return self._put(replace(record, status=GoalState.CANCELLED, updated_cycle=cycle))

    def set_priority(self, goal_id: str, priority: int, cycle: int) -> GoalStore:
        """Move a goal in the agent's goal list (lower number = more important)."""
        record = self.get(goal_id)
        if priority < 1:
            raise GoalStoreError(f"{goal_id}: priority must be >= 1, got {priority}")
        if record.status in _WITHDRAWN:
            raise GoalStoreError(f"{goal_id}: is {record.status.value}, cannot reprioritise")
        return self._put(replace(record, priority=priority, updated_cycle=cycle))

    def goal_list(self, agent: str) -> tuple[dict[str, Any], ...]:
        """What the executive of `agent` pursues: every goal not cancelled nor failed."""
        return tuple(g.brief() for g in self.for_agent(agent) if g.status not in _WITHDRAWN)

    def update_from_intention(self, agent: str, decision: dict[str, Any],
                              cycle: int) -> GoalStore:
        """Mirror the statuses the executive reported in `decision` (Decision.to_dict())."""
        reported = {g.get("id"): g for g in decision.get("goals", ())}
        store = self
        for record in self.for_agent(agent):
            if record.status in _WITHDRAWN or record.id not in reported:
                continue
            status = _FROM_ENGINE.get(str(reported[record.id].get("status")))
            if status is None or status is record.status:
                continue
            note = str(reported[record.id].get("note", "")) \
                if status in (GoalState.IMPASSE, GoalState.FAILED) else ""
            store = store._put(replace(record, status=status, updated_cycle=cycle, note=note))
        return store

    def mark_scripted(self, indexes: Iterable[int]) -> GoalStore:
        """Remember which scenario requests were applied, so a restart does not repeat them."""
        return replace(self, scripted_done=self.scripted_done | frozenset(indexes))

    def _put(self, record: GoalRecord) -> GoalStore:
        goals = tuple(record if g.id == record.id else g for g in self.goals)
        return replace(self, goals=goals)

    def to_json(self) -> dict[str, Any]:
        return {"version": STORE_VERSION, "next_id": self.next_id,
                "scripted_done": sorted(self.scripted_done),
                "goals": [g.to_dict() for g in self.goals]}

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> GoalStore:
        if doc.get("version") != STORE_VERSION:
            raise GoalStoreError(f"goal store version: expected {STORE_VERSION}, "
                                 f"got {doc.get('version')!r}")
        return cls(tuple(GoalRecord.from_dict(g) for g in doc.get("goals", ())),
                   int(doc.get("next_id", 1)), frozenset(doc.get("scripted_done", ())))


def save(store: GoalStore, path: Path) -> None:
    """Write atomically (temp file + rename), so a crash never leaves half a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(json.dumps(store.to_json(), indent=1))
    os.replace(tmp, path)


def load(path: Path) -> GoalStore:
    """The saved store, or an empty one when the file does not exist yet."""
    if not path.exists():
        return GoalStore()
    try:
        return GoalStore.from_json(json.loads(path.read_text()))
    except (ValueError, KeyError) as exc:
        raise GoalStoreError(f"{path}: unreadable goal store: {exc}") from exc
