"""The parsed program: concepts, skills, goals and resources (seed 000, Tables 1, 2, 5, 6)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .conjunction import Goal
from .errors import Diagnostic
from .terms import ActionTemplate, Literal, Loc, PerceptPattern, Test, Var


@dataclass(frozen=True, slots=True)
class ConceptClause:
    """One definition of a concept; several clauses for the same head are alternatives (or)."""

    head: Literal
    percepts: tuple[PerceptPattern, ...] = ()
    relations: tuple[Literal, ...] = ()
    tests: tuple[Test, ...] = ()
    loc: Loc | None = None
    index: int = 1  # 1-based clause number among this predicate's clauses

    @property
    def primitive(self) -> bool:
        """True when the clause refers to percepts only (no :relations)."""
        return not self.relations


@dataclass(frozen=True, slots=True)
class Skill:
    """A skill clause indexed by the concept (goal) it achieves.

    Exactly one of ``actions`` (primitive), ``subgoals`` (nonprimitive) or ``body`` (a step tree
    of SCS constructs, seed 002, read by the mechanism that reads bodies) is given; the path
    finder asks the runner of ``kind`` (agents/lang/execution/bodies.py).
    """

    head: Literal
    percepts: tuple[PerceptPattern, ...] = ()
    start: tuple = ()  # Literal | Test, checked when the skill is first entered
    requires: tuple = ()  # Literal | Test, checked on entry and while it continues
    subgoals: tuple[Literal, ...] = ()
    actions: tuple[ActionTemplate, ...] = ()
    body: Any = None  # a step tree (SCS, seed 002, Appendix C), read by a mechanism
    loc: Loc | None = None
    index: int = 1  # 1-based clause number among skills for this head predicate
    number: int = 0  # 0-based position among all skills (stable id inside a program)
    effects: tuple[Literal, ...] = ()  # a primitive skill's stated effects: adds, (not L) deletes

    @property
    def kind(self) -> str:
        """"primitive", "nonprimitive" or "body"."""
        if self.body is not None:
            return "body"
        return "primitive" if self.actions or not self.subgoals else "nonprimitive"

    @property
    def name(self) -> str:
        """Readable id such as ``at-address#2`` (second skill clause for at-address)."""
        return f"{self.head.pred}#{self.index}"

    def head_vars(self) -> list[Var]:
        return [a for a in self.head.args if isinstance(a, Var)]


@dataclass(frozen=True, slots=True)
class GoalSpec:
    """A goal as written in a program's (goals ...) section: a literal or a conjunction."""

    literal: Goal
    loc: Loc | None = None


@dataclass(frozen=True, eq=False)
class Program:
    """A checked program. ``strata`` lists the concept SCCs bottom-up: (preds, recursive);
    ``mechanisms``: those it was read with (agents/lang/core/mechanism.py), which run it."""

    concepts: dict[str, tuple[ConceptClause, ...]]
    arity: dict[str, int]
    skills: tuple[Skill, ...]
    goals: tuple[GoalSpec, ...]
    resources: dict[str, frozenset[str]] | None = None
    strata: tuple[tuple[tuple[str, ...], bool], ...] = ()
    warnings: tuple[Diagnostic, ...] = ()
    sources: tuple[str, ...] = ()
    skills_by_pred: dict[str, tuple[Skill, ...]] = field(default_factory=dict)
    sections: dict[str, tuple] = field(default_factory=dict)  # a mechanism's own sections
    mechanisms: tuple = ()

    def skills_for(self, pred: str) -> tuple[Skill, ...]:
        """Skills whose head is ``pred``, in program order."""
        return self.skills_by_pred.get(pred, ())

    def actions(self) -> tuple[ActionTemplate, ...]:
        """Every action the program can send its world, in program order: skills' :actions,
        the atomic actions of SCS bodies (seed 002), operators' :actions and :on-failure
        (seed 003): Mechanism.body_actions and program_actions."""
        out: list[ActionTemplate] = []
        for skill in self.skills:
            out.extend(skill.actions)
            if skill.body is not None:
                for m in self.mechanisms:
                    out.extend(m.body_actions(skill.body))
        for m in self.mechanisms:
            out.extend(m.program_actions(self))
        return tuple(out)
