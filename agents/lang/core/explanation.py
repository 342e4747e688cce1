"""Decisions and their explanation: goal statuses, chosen path(s) with bindings, and why each
alternative skill was passed over (seed 000, "Inference and Execution Mechanisms")."""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any, Protocol

from .terms import Action, fmt


class GoalStatus(StrEnum):
    """Status of a goal in one cycle."""

    SATISFIED = "satisfied"   # every instance holds
    ACTIVE = "active"         # this goal's skill path acts this cycle
    SUSPENDED = "suspended"   # unsatisfied, has a remembered path, a more important goal acts
    IMPASSE = "impasse"       # unsatisfied and no executable skill path exists
    FAILED = "failed"         # given up on: every alternative failed (the reason in the note)
    PENDING = "pending"       # unsatisfied, not reached this cycle


@dataclass(frozen=True, slots=True)
class GoalReport:
    id: str
    goal: str
    priority: int
    status: GoalStatus
    bindings: tuple = ()   # ((var, value), ...) of the instance worked on
    instance: str = ""     # the instance worked on (or the first unsatisfied one)
    note: str = ""

    def to_dict(self) -> dict:
        return {"id": self.id, "goal": self.goal, "priority": self.priority,
                "status": self.status.value, "bindings": dict(self.bindings),
                "instance": self.instance, "note": self.note}


@dataclass(frozen=True, slots=True)
class PathStep:
    goal: str       # the goal instance this skill achieves
    skill: str      # e.g. at-address#2
    where: str      # file:line:col of the skill
    bindings: tuple  # ((var, value), ...)
    mode: str       # "continued" (kept from last cycle), "resumed" (kept after a suspension,
                    # every :start holding again) or "entered"

    def to_dict(self) -> dict:
        return {"goal": self.goal, "skill": self.skill, "where": self.where,
                "bindings": dict(self.bindings), "mode": self.mode}


@dataclass(frozen=True, slots=True)
class PassOver:
    goal_id: str
    depth: int
    goal: str
    skill: str      # "" when no skill exists for the goal
    bindings: tuple
    reason: str

    def to_dict(self) -> dict:
        return {"goal_id": self.goal_id, "depth": self.depth, "goal": self.goal,
                "skill": self.skill, "bindings": dict(self.bindings), "reason": self.reason}


@dataclass(frozen=True, slots=True)
class GoalPath:
    """The path one goal executes this cycle; ``parallel`` when it acts through free resources."""

    goal_id: str
    steps: tuple[PathStep, ...]
    actions: tuple[Action, ...]
    resources: tuple[str, ...] = ()
    parallel: bool = False

    def to_dict(self) -> dict:
        return {"goal_id": self.goal_id, "path": [s.to_dict() for s in self.steps],
                "actions": [a.to_list() for a in self.actions],
                "resources": list(self.resources), "parallel": self.parallel}


class Section(Protocol):
    """A mechanism's part of a decision (the problem solver's goal stacks, SCS threads, a
    plan): plain data for the bus and readable lines for people."""

    name: str

    def to_dict(self) -> dict[str, Any]: ...

    def lines(self) -> list[str]: ...


@dataclass(frozen=True, slots=True)
class Decision:
    """One cycle's executive decision. ``actions`` is the cycle's output; ``sections`` hold
    what each mechanism that took part has to say (keyed by ``Section.name`` in to_dict)."""

    cycle: int
    goals: tuple[GoalReport, ...]
    paths: tuple[GoalPath, ...] = ()
    why: tuple[PassOver, ...] = field(default=())
    sections: tuple[Section, ...] = field(default=())

    def section(self, name: str) -> Section | None:
        """The section a mechanism called ``name`` added this cycle, if any."""
        return next((s for s in self.sections if s.name == name), None)

    @property
    def actions(self) -> tuple[Action, ...]:
        return tuple(a for p in self.paths for a in p.actions)

    @property
    def path(self) -> tuple[PathStep, ...]:
        """The path of the most important acting goal (empty if none acts)."""
        return self.paths[0].steps if self.paths else ()

    def status_of(self, goal_id: str) -> GoalStatus:
        return next(g.status for g in self.goals if g.id == goal_id)

    def to_dict(self) -> dict:
        """JSON/msgpack-able: goals, path (main), actions (all), parallel paths, why."""
        return {"cycle": self.cycle, "goals": [g.to_dict() for g in self.goals],
                "goal_id": self.paths[0].goal_id if self.paths else "",
                "path": [s.to_dict() for s in self.path],
                "resources": list(self.paths[0].resources) if self.paths else [],
                "actions": [a.to_list() for a in self.actions],
                "parallel": [p.to_dict() for p in self.paths[1:]],
                "why": [w.to_dict() for w in self.why],
                **{s.name: s.to_dict() for s in self.sections}}

    def explain(self) -> str:
        """Human-readable explanation (format documented in docs/language.md)."""
        lines = [f"cycle {self.cycle}", "goals:"]
        for g in self.goals:
            extra = f"  [{g.instance}]" if g.instance and g.instance != g.goal else ""
            note = f"  -- {g.note}" if g.note else ""
            lines.append(f"  {g.priority:>3} {g.id:<8} {g.status.value:<9} {g.goal}{extra}{note}")
        for p in self.paths:
            tag = " (parallel, resources: " + " ".join(p.resources) + ")" if p.parallel else ""
            lines.append(f"path of {p.goal_id}{tag}:")
            for depth, s in enumerate(p.steps):
                lines.append(f"  {'  ' * depth}{s.goal} <- {s.skill} [{s.mode}] "
                             f"{_bind(s.bindings)}  ({s.where})")
            lines.append("  actions: " + (" ".join(str(a) for a in p.actions) or "none"))
        if not self.paths:
            lines.append("path: none (no goal acts this cycle)")
        for section in self.sections:
            lines += section.lines()
        if self.why:
            lines.append("passed over:")
            for w in self.why:
                skill = w.skill or "-"
                lines.append(f"  {w.goal_id}: {'  ' * w.depth}{w.goal} {skill} "
                             f"{_bind(w.bindings)}: {w.reason}")
        return "\n".join(lines)


def _bind(b: tuple) -> str:
    return "{" + ", ".join(f"?{k}={fmt(v)}" for k, v in b) + "}"
