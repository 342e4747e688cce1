"""The kinds of skill body and the runner of each (one interface for every skill body, as
py_trees ticks every behaviour through one): ``Skill.kind`` names the kind; the path finder
asks its runner for the path below an entered skill. A new kind (an SCS body, a learned or
planned skill) is a mechanism's runner
(Mechanism.runners), not a new branch in the path finder. A runner that keeps state across
cycles may also be a ``CycleHook``: the executive calls ``begin`` before each cycle's goal
walk and ``end`` after it (the SCS runner settles action outcomes and shows its threads
there)."""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from ..core.arith import evaluate
from ..core.errors import EvalError
from ..core.explanation import GoalReport
from ..core.matcher import ground
from ..core.terms import Action
from ..reading.goals import satisfied
from .paths import BodyRunner, PathFinder, Walk


@runtime_checkable
class CycleHook(Protocol):
    """A mechanism's work at the start and the end of every cycle's goal walk."""

    def begin(self, finder: PathFinder, walk: Walk) -> None: ...

    def end(self, finder: PathFinder, walk: Walk, reports: list[GoalReport]) -> None: ...


def body_runners(mechanisms: tuple = ()) -> dict[str, BodyRunner]:
    """``Skill.kind`` -> runner, for every kind this engine can execute: the kernel's two and
    the mechanisms' (Mechanism.runners: the SCS body, seed 002)."""
    out: dict[str, BodyRunner] = {"primitive": PrimitiveBody(), "nonprimitive": SubgoalBody()}
    for m in mechanisms:
        out.update(m.runners())
    return out


def cycle_hooks(runners: dict[str, BodyRunner], program_kinds: set[str]) -> list[CycleHook]:
    """The runners, of the kinds a program uses, that want to hear of every cycle."""
    return [r for kind, r in runners.items() if kind in program_kinds
            and isinstance(r, CycleHook)]


class PrimitiveBody:
    """A primitive skill: its actions, evaluated under the bindings, if their resources are
    free (seed 000, Table 1: ``:actions ((*gas 6.25))``)."""

    def expand(self, finder, walk, s, b, goal, prev_rest, depth, on_path, step, stored):
        try:
            actions = [Action(a.name, tuple(evaluate(x, b) for x in a.args)) for a in s.actions]
        except EvalError as exc:
            walk.passed(depth, str(goal), s.name, b, f"action cannot be evaluated: {exc}")
            return None
        clash = finder.conflict(walk, actions) or finder.undoes(walk, actions)
        if clash:
            walk.passed(depth, str(goal), s.name, b, clash)
            return None
        return [step], actions, [stored]


class SubgoalBody:
    """A nonprimitive skill: a path for its first unsatisfied subgoal (seed 000, Table 1:
    ``:subgoals ((address-in-front ...) (at-address ...))``)."""

    def expand(self, finder, walk, s, b, goal, prev_rest, depth, on_path, step, stored):
        sub = next((g for g in (ground(x, b) for x in s.subgoals)
                    if not satisfied(g, walk.store)), None)
        if sub is None:
            walk.passed(depth, str(goal), s.name, b,
                        "every subgoal already holds (goal still false)")
            return None
        found = finder.achieve(walk, sub, prev_rest, depth + 1, on_path)
        if found is None:
            walk.passed(depth, str(goal), s.name, b, f"subgoal {sub} has no executable path")
            return None
        steps, actions, st = found
        return [step, *steps], actions, [stored, *st]
