"""The kinds of skill body and the runner of each (STYLE.md, "One interface for every skill
body"): ``Skill.kind`` names the kind; the path finder asks its runner for the path below an
entered skill. A new kind (an SCS body, a learned or planned skill) is a new runner here,
not a new branch in the path finder. A runner that keeps state across cycles may also be a
``CycleHook``: the executive calls ``begin`` before each cycle's goal walk and ``end`` after
it (the SCS runner settles action outcomes and shows its threads there)."""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from .explanation import GoalReport
from .paths import BodyRunner, PathFinder, PrimitiveBody, SubgoalBody, Walk
from .scs.runner import ScsBody


@runtime_checkable
class CycleHook(Protocol):
    """A mechanism's work at the start and the end of every cycle's goal walk."""

    def begin(self, finder: PathFinder, walk: Walk) -> None: ...

    def end(self, finder: PathFinder, walk: Walk, reports: list[GoalReport]) -> None: ...


def body_runners() -> dict[str, BodyRunner]:
    """``Skill.kind`` -> runner, for every kind this engine can execute."""
    return {"primitive": PrimitiveBody(), "nonprimitive": SubgoalBody(), "body": ScsBody()}


def cycle_hooks(runners: dict[str, BodyRunner], program_kinds: set[str]) -> list[CycleHook]:
    """The runners, of the kinds a program uses, that want to hear of every cycle."""
    return [r for kind, r in runners.items() if kind in program_kinds
            and isinstance(r, CycleHook)]
