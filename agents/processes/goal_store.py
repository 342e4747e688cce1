"""The goal-entry process's memory: user goals with their statuses, as a frozen value.

Pure: every operation returns a new GoalStore; agents/processes/goal_file.py saves and
recovers it. ROGUE (seed 003) takes requests asynchronously with priorities and keeps each
task's state through suspension and resumption; here the executive reports each goal's status
in its intention and the store mirrors it. Requests are bounded (docs/bus.md, "Goal
requests"): a goal's length, the priority range, the live goals per agent; and the store
keeps only the latest withdrawn goals of each agent, so it stays small.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from enum import StrEnum
from typing import Any

from agents.lang.core.limits import MAX_GOAL_CHARS, shorten
from bus.schema import FieldError, ListOf, Record, Str

STORE_VERSION = 1
MAX_PRIORITY = 1_000_000
"""Priorities are 1..MAX_PRIORITY (lower is more important); program goals have 1..n."""
MAX_LIVE_GOALS = 16
"""User goals per agent still to be achieved (pending, active, suspended, impasse: the
executive looks for a path for each every cycle, a cost per goal and cycle); a post
beyond it is refused. Achieved goals do not count: checking that one still holds is cheap,
and an agent that has done 16 errands takes a 17th (seed 003's office robot serves requests
all day)."""
MAX_KEPT_WITHDRAWN = 100
"""Cancelled and failed goals kept per agent (for `teleo goal list`); older ones are dropped."""
MAX_DEADLINE = 100_000_000
"""[cycles] the longest deadline a goal may be given."""
MAX_ID_CHARS = 32
"""[characters] of a goal id in a request (ids are g1, g2, ...)."""


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
# Statuses whose note (why it waits, why it failed) the user sees in `teleo goal list`.
_NOTED = frozenset({GoalState.PENDING, GoalState.IMPASSE, GoalState.FAILED})
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
    once: bool = False   # dropped when achieved (the executive ends it), not kept
    deadline: int = 0    # [cycles] failed unless achieved within them (0: none)

    def to_dict(self) -> dict[str, Any]:
        return {"id": self.id, "agent": self.agent, "goal": self.goal, "priority": self.priority,
                "status": self.status.value, "posted_cycle": self.posted_cycle,
                "updated_cycle": self.updated_cycle, "note": self.note, **self._ends()}

    def _ends(self) -> dict[str, Any]:
        """once and deadline, only when set (a goal without them is written as before)."""
        return {**({"once": True} if self.once else {}),
                **({"deadline": self.deadline} if self.deadline else {})}

    @classmethod
    def from_dict(cls, d: object, where: str = "goal") -> GoalRecord:
        """Read one saved record; raises GoalStoreError naming `where` and the bad field."""
        if not isinstance(d, dict):
            raise GoalStoreError(f"{where}: expected an object, got {_kind(d)}")
        status = _field(d, "status", str, where)
        if status not in {s.value for s in GoalState}:
            raise GoalStoreError(f"{where}: status {shorten(status)!r} is not one of "
                                 f"{', '.join(s.value for s in GoalState)}")
        return cls(_field(d, "id", str, where), _field(d, "agent", str, where),
                   _field(d, "goal", str, where), _field(d, "priority", int, where),
                   GoalState(status), _field(d, "posted_cycle", int, where, 0),
                   _field(d, "updated_cycle", int, where, 0), _field(d, "note", str, where, ""),
                   _field(d, "once", bool, where, False), _field(d, "deadline", int, where, 0))

    def brief(self) -> dict[str, Any]:
        """The GoalList entry form: {id, goal, priority, status} (docs/architecture.md)."""
        return {"id": self.id, "goal": self.goal, "priority": self.priority,
                "status": self.status.value, **self._ends()}


@dataclass(frozen=True)
class GoalStore:
    """All user goals of a run, in posting order, with the bookkeeping a restart needs."""

    goals: tuple[GoalRecord, ...] = ()
    next_id: int = 1
    scripted_done: frozenset[int] = field(default_factory=frozenset)
    incidents: tuple[str, ...] = ()  # what recovery from a damaged file did (goal_file.py)
    refused: tuple[str, ...] = ()    # the scenario's requests refused, for the summary

    def get(self, goal_id: str) -> GoalRecord:
        for record in self.goals:
            if record.id == goal_id:
                return record
        known = [g.id for g in self.goals][-10:]
        raise GoalStoreError(f"no goal {shorten(goal_id)!r} (latest known: {known})")

    def for_agent(self, agent: str | None = None) -> tuple[GoalRecord, ...]:
        return tuple(g for g in self.goals if agent is None or g.agent == agent)

    def post(self, agent: str, goal: str, priority: int, cycle: int,
             validate: Validator, once: bool = False,
             deadline: int = 0) -> tuple[GoalStore, GoalRecord]:
        """Add a goal after the agent's program accepted it; raises GoalStoreError if refused
        (too long, priority out of range, MAX_LIVE_GOALS reached, a duplicate, or the
        program's reason)."""
        if len(goal) > MAX_GOAL_CHARS:
            raise GoalStoreError(f"goal {shorten(goal)!r}: longer than {MAX_GOAL_CHARS} "
                                 "characters")
        text = " ".join(goal.split())
        _check_priority(text, priority)
        live = [g for g in self.for_agent(agent) if g.status not in _WITHDRAWN]
        if sum(g.status is not GoalState.ACHIEVED for g in live) >= MAX_LIVE_GOALS:
            raise GoalStoreError(f"{text}: {agent} has {MAX_LIVE_GOALS} live goals, the limit; "
                                 "cancel one first (teleo goal cancel ID)")
        for other in live:
            if other.goal == text and other.status is not GoalState.ACHIEVED:
                raise GoalStoreError(f"{text}: already posted for {agent} as {other.id}")
        reason = validate(agent, text, priority)
        if reason:
            raise GoalStoreError(f"{agent} cannot take {reason}")  # its reason names the goal
        if type(deadline) is not int or not 0 <= deadline <= MAX_DEADLINE:
            raise GoalStoreError(f"{text}: deadline must be a number of cycles in "
                                 f"1..{MAX_DEADLINE}, got {shorten(repr(deadline))}")
        record = GoalRecord(f"g{self.next_id}", agent, text, priority, GoalState.PENDING,
                            cycle, cycle, once=bool(once), deadline=deadline)
        return replace(self, goals=self.goals + (record,), next_id=self.next_id + 1), record

    def cancel(self, goal_id: str, cycle: int, force: bool = False) -> GoalStore:
        """Withdraw a goal; the executive drops it from the next goal list it receives. An
        achieved goal is refused like a cancelled one (its record says what happened), unless
        `force`: the agent keeps an achieved goal and acts again should it stop holding, so
        withdrawing one is a real change (then its note says it had been achieved)."""
        record = self.get(goal_id)
        if record.status is GoalState.CANCELLED:
            raise GoalStoreError(f"{goal_id}: already cancelled")
        note = ""
        if record.status is GoalState.ACHIEVED:
            if not force:
                raise GoalStoreError(
                    f"{goal_id}: already achieved (cycle {record.updated_cycle}); an achieved "
                    "goal stays achieved (force the cancel to stop the agent keeping it)")
            note = f"achieved at cycle {record.updated_cycle}, then withdrawn"
        return self._put(replace(record, status=GoalState.CANCELLED, updated_cycle=cycle,
                                 note=note))

    def set_priority(self, goal_id: str, priority: int, cycle: int) -> GoalStore:
        """Move a goal in the agent's goal list (lower number = more important)."""
        record = self.get(goal_id)
        _check_priority(goal_id, priority)
        if record.status in _WITHDRAWN:
            raise GoalStoreError(f"{goal_id}: is {record.status.value}, cannot reprioritise")
        return self._put(replace(record, priority=priority, updated_cycle=cycle))

    def goal_list(self, agent: str) -> tuple[dict[str, Any], ...]:
        """What the executive of `agent` pursues: every goal not cancelled nor failed."""
        return tuple(g.brief() for g in self.for_agent(agent) if g.status not in _WITHDRAWN)

    def update_from_intention(self, agent: str, decision: dict[str, Any],
                              cycle: int) -> GoalStore:
        """Mirror the statuses the executive reported in `decision` (Decision.to_dict());
        raises GoalStoreError naming the field of a decision that does not fit DECISION."""
        try:
            DECISION.check(decision)
        except FieldError as exc:
            raise GoalStoreError(f"intention of {shorten(agent)} at cycle {cycle}: decision."
                                 f"{exc}") from None
        reported = {g["id"]: g for g in decision.get("goals", ())}
        store = self
        for record in self.for_agent(agent):
            if record.status in _WITHDRAWN or record.id not in reported:
                continue
            status = _FROM_ENGINE.get(str(reported[record.id].get("status")))
            note = str(reported[record.id].get("note", "")) if status in _NOTED else ""
            if status is None or (status is record.status and note == record.note):
                continue
            when = cycle if status is not record.status else record.updated_cycle
            store = store._put(replace(record, status=status, updated_cycle=when, note=note))
        return store

    def mark_scripted(self, indexes: Iterable[int]) -> GoalStore:
        """Remember which scenario requests were applied, so a restart does not repeat them."""
        return replace(self, scripted_done=self.scripted_done | frozenset(indexes))

    def noted(self, incident: str) -> GoalStore:
        """The store with `incident` (what a recovery did) remembered for the run's summary."""
        return replace(self, incidents=self.incidents + (incident,))

    def refusing(self, request: str) -> GoalStore:
        """The store with a refused scripted request (what, when, why) remembered."""
        return replace(self, refused=self.refused + (request,))

    def _put(self, record: GoalRecord) -> GoalStore:
        goals = tuple(record if g.id == record.id else g for g in self.goals)
        return replace(self, goals=_trimmed(goals, record.agent))

    def to_json(self) -> dict[str, Any]:
        return {"version": STORE_VERSION, "next_id": self.next_id,
                "scripted_done": sorted(self.scripted_done),
                "goals": [g.to_dict() for g in self.goals], "incidents": list(self.incidents),
                "refused": list(self.refused)}

    @classmethod
    def from_json(cls, doc: object) -> GoalStore:
        """Read a saved store; raises GoalStoreError saying what is wrong with its shape."""
        if not isinstance(doc, dict):
            raise GoalStoreError(f'expected an object {{"version": {STORE_VERSION}, "goals": '
                                 f"[...]}}, got {_kind(doc)}")
        if doc.get("version") != STORE_VERSION:
            raise GoalStoreError(f"version: expected {STORE_VERSION}, "
                                 f"got {shorten(repr(doc.get('version')))}")
        goals = _field(doc, "goals", list, "store", [])
        records = tuple(GoalRecord.from_dict(g, f"goals[{i}]") for i, g in enumerate(goals))
        ids = [r.id for r in records]
        if len(set(ids)) != len(ids):
            raise GoalStoreError(f"goals: an id is used twice in {shorten(str(ids), 200)}")
        next_id = _field(doc, "next_id", int, "store", len(records) + 1)
        numbers = [int(i[1:]) for i in ids if i[:1] == "g" and i[1:].isdigit()]
        if next_id <= max(numbers, default=0):
            raise GoalStoreError(f"next_id {next_id} would give an id already used "
                                 f"(g{max(numbers)})")
        done = _field(doc, "scripted_done", list, "store", [])
        incidents = _field(doc, "incidents", list, "store", [])
        refused = _field(doc, "refused", list, "store", [])
        if not all(type(i) is int for i in done) or \
                not all(isinstance(i, str) for i in (*incidents, *refused)):
            raise GoalStoreError("scripted_done must list integers, incidents and refused "
                                 "strings")
        return cls(records, next_id, frozenset(done), tuple(incidents), tuple(refused))


def _check_priority(what: str, priority: int) -> None:
    if type(priority) is not int or not 1 <= priority <= MAX_PRIORITY:
        raise GoalStoreError(f"{what}: priority must be an integer in 1..{MAX_PRIORITY}, "
                             f"got {shorten(repr(priority))}")


def _trimmed(goals: tuple[GoalRecord, ...], agent: str) -> tuple[GoalRecord, ...]:
    """`goals` without the oldest withdrawn goals of `agent` beyond MAX_KEPT_WITHDRAWN."""
    withdrawn = [g.id for g in goals if g.agent == agent and g.status in _WITHDRAWN]
    drop = set(withdrawn[:-MAX_KEPT_WITHDRAWN])
    return tuple(g for g in goals if g.id not in drop) if drop else goals


def _kind(value: object) -> str:
    return "null" if value is None else type(value).__name__


def _field(d: dict, name: str, kind: type, where: str, default: Any = ...) -> Any:
    """d[name], checked to be a `kind` (bool is not an int); `default` when absent."""
    if name not in d:
        if default is ...:
            raise GoalStoreError(f"{where}: lacks {name!r}")
        return default
    value = d[name]
    if type(value) is not kind:
        raise GoalStoreError(f"{where}.{name}: expected {kind.__name__}, got "
                             f"{shorten(repr(value))}")
    return value


DECISION = Record({}, {"goals": ListOf(Record({"id": Str(), "status": Str()},
                                              {"note": Str(max_len=4096)}, open=True,
                                              what="a goal {id, status, note}"))},
                  open=True, what="a decision")
"""What the goal-entry process reads of an executive's intention (the engine's
Decision.to_dict(), checked as plain data by the codec): each goal's id, status and note."""
