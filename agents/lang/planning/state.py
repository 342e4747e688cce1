"""The planner's part of EngineState (seed 003): one task per request with its tail-plan, the
step being executed, the head-plan (every operator applied, with what monitoring found), the
facts only the planner knows (its state model), and the travel figures; kept between cycles
and across a restart of the executive process (to_dict/from_dict). Literals and commands are
plain data (text, lists), so the state is msgpack- and JSON-able."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any


@dataclass(frozen=True, slots=True)
class PlanStep:
    """One operator instance: ``name`` and ``args`` (``<goto-pickup-loc mitchell r-5303>``),
    ``clause`` (its index among the program's operators), ``bindings``, ``achieves`` (the
    literal it was chosen for), ``primary`` (its head, ground), ``conditions`` (its
    preconditions, ground), ``effects`` (ground; a variable left in a negated one means any
    value), ``actions`` (the commands that execute it), ``on_failure`` (commands announced
    when it ends without its primary effect), ``place`` (where the robot is while or after
    doing it, in the plan's projection; "" when unknown)."""

    name: str
    args: tuple
    clause: int
    bindings: tuple[tuple[str, Any], ...]
    achieves: str
    primary: str
    conditions: tuple[str, ...]
    effects: tuple[str, ...]
    actions: tuple[tuple, ...]
    on_failure: tuple[tuple, ...] = ()
    place: str = ""

    @property
    def text(self) -> str:
        return "<" + " ".join([self.name, *(str(a) for a in self.args)]) + ">"

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "args": list(self.args), "clause": self.clause,
                "bindings": [[k, v] for k, v in self.bindings], "achieves": self.achieves,
                "primary": self.primary, "conditions": list(self.conditions),
                "effects": list(self.effects), "actions": [list(a) for a in self.actions],
                "on_failure": [list(a) for a in self.on_failure], "place": self.place}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> PlanStep:
        return cls(str(d["name"]), tuple(d["args"]), int(d["clause"]),
                   tuple((str(k), v) for k, v in d["bindings"]), str(d["achieves"]),
                   str(d["primary"]), _texts(d["conditions"]), _texts(d["effects"]),
                   tuple(tuple(a) for a in d["actions"]),
                   tuple(tuple(a) for a in d.get("on_failure", ())), str(d.get("place", "")))


@dataclass(frozen=True, slots=True)
class Exclusion:
    """A choice the planner will not make again while the situation it failed in persists
    (seed 003, section 6: the execution of an action failed, "it will backtrack to find a
    different action which can achieve the goal"): operator instance ``step`` (its name and
    bindings, ``<observe-conference-room r-5309>``) for the literal ``achieves``, excluded at
    cycle ``since`` because ``why``; it stands while every fact of ``depends`` holds (what the
    step brought to light, ``(room-occupied r-5309)``; none: while ``achieves`` does not
    hold); ``opened``: the cycle it was opened again (-1 while it stands), with ``reopened``
    saying why."""

    step: str
    achieves: str
    since: int
    why: str
    depends: tuple[str, ...] = ()
    opened: int = -1
    reopened: str = ""

    @property
    def standing(self) -> bool:
        return self.opened < 0

    def describe(self) -> str:
        """One line for the explanation and the summary."""
        base = f"{self.step} for {self.achieves} excluded at cycle {self.since}: {self.why}"
        if not self.standing:
            return f"{base}; open again at cycle {self.opened}: {self.reopened}"
        held = " ".join(self.depends) if self.depends else f"(not {self.achieves})"
        return f"{base}; stands while {held} holds"

    def to_dict(self) -> dict[str, Any]:
        return {"step": self.step, "achieves": self.achieves, "since": self.since,
                "why": self.why, "depends": list(self.depends), "opened": self.opened,
                "reopened": self.reopened}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Exclusion:
        return cls(str(d["step"]), str(d["achieves"]), int(d["since"]), str(d["why"]),
                   _texts(d.get("depends")), int(d.get("opened", -1)),
                   str(d.get("reopened", "")))


@dataclass(frozen=True, slots=True)
class Task:
    """One request: its goal, priority and arrival order (``seq``, ``arrived`` cycle), the
    knowledge added when it arrived, its tail-plan, ``status`` (new, selected, waiting,
    blocked) with a ``note``, ``places`` (where steps for it were executed, in order),
    ``failures`` (steps that failed or did not achieve their effect), ``blocked_since`` (the
    cycle its next place became unreachable, -1), ``retry_at`` (no step of it before that
    cycle, after a failure), ``replan`` (why its tail-plan must be made afresh: a step
    of it did not achieve its effect; "" when it may be kept while it holds) and
    ``excluded`` (the choices its failed steps excluded, standing or opened again)."""

    goal_id: str
    goal: str
    priority: int
    seq: int
    arrived: int
    knowledge: tuple[str, ...] = ()
    plan: tuple[PlanStep, ...] = ()
    status: str = "new"
    note: str = ""
    places: tuple[str, ...] = ()
    failures: int = 0
    blocked_since: int = -1
    retry_at: int = -1
    replan: str = ""
    excluded: tuple[Exclusion, ...] = ()

    def standing(self) -> tuple[Exclusion, ...]:
        """The exclusions that stand now."""
        return tuple(x for x in self.excluded if x.standing)

    def to_dict(self) -> dict[str, Any]:
        return {"goal_id": self.goal_id, "goal": self.goal, "priority": self.priority,
                "seq": self.seq, "arrived": self.arrived, "knowledge": list(self.knowledge),
                "plan": [s.to_dict() for s in self.plan], "status": self.status,
                "note": self.note, "places": list(self.places), "failures": self.failures,
                "blocked_since": self.blocked_since, "retry_at": self.retry_at,
                "replan": self.replan, "excluded": [x.to_dict() for x in self.excluded]}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Task:
        return cls(str(d["goal_id"]), str(d["goal"]), int(d["priority"]), int(d["seq"]),
                   int(d["arrived"]), _texts(d.get("knowledge")),
                   tuple(PlanStep.from_dict(s) for s in d.get("plan", ())),
                   str(d.get("status", "new")), str(d.get("note", "")),
                   _texts(d.get("places")), int(d.get("failures", 0)),
                   int(d.get("blocked_since", -1)), int(d.get("retry_at", -1)),
                   str(d.get("replan", "")),
                   tuple(Exclusion.from_dict(x) for x in d.get("excluded", ())))


@dataclass(frozen=True, slots=True)
class Executing:
    """A step whose commands were sent at cycle ``sent`` for the tasks ``tasks`` (the first
    one's plan named it); ``waiting``: commands whose outcome has not come back; ``failed``:
    the first failure reported ("" while none); ``before``: the perceived facts about the
    step's objects when it was chosen (what it brings to light is judged against them)."""

    step: PlanStep
    tasks: tuple[str, ...]
    sent: int
    waiting: tuple[tuple, ...]
    failed: str = ""
    before: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return {"step": self.step.to_dict(), "tasks": list(self.tasks), "sent": self.sent,
                "waiting": [list(a) for a in self.waiting], "failed": self.failed,
                "before": list(self.before)}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Executing:
        return cls(PlanStep.from_dict(d["step"]), _texts(d["tasks"]), int(d["sent"]),
                   tuple(tuple(a) for a in d["waiting"]), str(d.get("failed", "")),
                   _texts(d.get("before")))


@dataclass(frozen=True, slots=True)
class Applied:
    """One entry of the head-plan: the step, the tasks it served, the cycle its commands
    were sent (or it was applied in the model) and ended, and what monitoring found:
    ``result`` verified | applied (no command: the model only) | false-success |
    not-achieved | failed | interrupted (cancelled, not failed: by the world's safe action
    for a late agent) | abandoned (no request needs it any more), with ``note``."""

    step: str
    tasks: tuple[str, ...]
    sent: int
    ended: int
    result: str
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"step": self.step, "tasks": list(self.tasks), "sent": self.sent,
                "ended": self.ended, "result": self.result, "note": self.note}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Applied:
        return cls(str(d["step"]), _texts(d["tasks"]), int(d["sent"]), int(d["ended"]),
                   str(d["result"]), str(d.get("note", "")))


@dataclass(frozen=True, slots=True)
class Finished:
    """A request no longer pending: ``status`` achieved | failed | cancelled, with the
    reason, the places where steps for it were executed and the choices its failed steps
    excluded."""

    goal_id: str
    goal: str
    priority: int
    seq: int
    arrived: int
    ended: int
    status: str
    reason: str = ""
    places: tuple[str, ...] = ()
    excluded: tuple[Exclusion, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return {"goal_id": self.goal_id, "goal": self.goal, "priority": self.priority,
                "seq": self.seq, "arrived": self.arrived, "ended": self.ended,
                "status": self.status, "reason": self.reason, "places": list(self.places),
                "excluded": [x.to_dict() for x in self.excluded]}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Finished:
        return cls(str(d["goal_id"]), str(d["goal"]), int(d["priority"]), int(d["seq"]),
                   int(d["arrived"]), int(d["ended"]), str(d["status"]),
                   str(d.get("reason", "")), _texts(d.get("places")),
                   tuple(Exclusion.from_dict(x) for x in d.get("excluded", ())))


@dataclass(frozen=True, slots=True)
class Travel:
    """``start``: where the robot was when the first request arrived; ``route``: the places
    of the steps executed since, in order; ``executed_m`` the route's length and
    ``fcfs_m`` that of serving the same requests first come, first served, both by the
    map's path distances [m] (seed 003, section 4)."""

    start: str = ""
    route: tuple[str, ...] = ()
    executed_m: float = 0.0
    fcfs_m: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {"start": self.start, "route": list(self.route),
                "executed_m": self.executed_m, "fcfs_m": self.fcfs_m}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Travel:
        return cls(str(d.get("start", "")), _texts(d.get("route")),
                   float(d.get("executed_m", 0.0)), float(d.get("fcfs_m", 0.0)))


MAX_LOG = 60   # monitoring and planning events kept [entries]


@dataclass(frozen=True, slots=True)
class PlannerState:
    """Everything the planner keeps: ``tasks`` (pending requests, by arrival), ``executing``,
    ``proposed`` (the step chosen this cycle before the goal walk commits it; never carried
    to the next cycle), ``announce`` (commands to say this cycle), ``head`` (the head-plan),
    ``model`` (facts only the planner knows, text), ``finished`` requests, ``travel`` and
    ``log`` (the last MAX_LOG events, "cycle N: ...")."""

    tasks: tuple[Task, ...] = ()
    executing: Executing | None = None
    proposed: Executing | None = None
    announce: tuple[tuple, ...] = ()
    head: tuple[Applied, ...] = ()
    model: tuple[str, ...] = ()
    finished: tuple[Finished, ...] = ()
    travel: Travel = field(default_factory=Travel)
    log: tuple[str, ...] = ()

    def task(self, goal_id: str) -> Task | None:
        return next((t for t in self.tasks if t.goal_id == goal_id), None)

    def with_log(self, events: list[str]) -> PlannerState:
        return replace(self, log=(self.log + tuple(events))[-MAX_LOG:]) if events else self

    def to_dict(self) -> dict[str, Any]:
        if self == PlannerState():
            return {}
        return {"tasks": [t.to_dict() for t in self.tasks],
                "executing": None if self.executing is None else self.executing.to_dict(),
                "head": [a.to_dict() for a in self.head], "model": list(self.model),
                "finished": [f.to_dict() for f in self.finished],
                "travel": self.travel.to_dict(), "log": list(self.log)}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> PlannerState:
        ex = d.get("executing")
        return cls(tuple(Task.from_dict(t) for t in d.get("tasks", ())),
                   None if ex is None else Executing.from_dict(ex), None, (),
                   tuple(Applied.from_dict(a) for a in d.get("head", ())),
                   _texts(d.get("model")),
                   tuple(Finished.from_dict(f) for f in d.get("finished", ())),
                   Travel.from_dict(d.get("travel", {})), _texts(d.get("log")))


def _texts(items: Any) -> tuple[str, ...]:
    return tuple(str(x) for x in items or ())
