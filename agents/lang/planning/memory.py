"""Failure memory (seed 003, section 6): "This update has the direct effect of indicating to
PRODIGY that the execution of an action failed, and it will backtrack to find a different
action which can achieve the goal."

A step whose expected (primary) effect does not hold after it excludes that operator with
those bindings for the literal it was chosen for, in its request, while the situation it was
judged in persists: what the step brought to light (the perceived facts about its objects
that hold after it and did not when it was chosen: ``(room-occupied r-5309)`` after
``<observe-conference-room r-5309>``) still holds; when it brought nothing to light, while
its effect does not hold. The back-chainer then passes the excluded choice over and
backtracks to the next alternative (agents/lang/planning/backchain.py); when the world
changes what the exclusion depended on (the room is observed empty later), the choice is
open again and the request is planned afresh. Pure."""

from __future__ import annotations

from dataclasses import replace

from ..core.store import FactStore
from ..core.terms import Literal
from .domain import Domain
from .state import Exclusion, PlanStep, Task


def objects(step: PlanStep) -> frozenset[str]:
    """The constants a step is about (its operator's arguments)."""
    return frozenset(a for a in step.args if isinstance(a, str))


def perceived_about(dom: Domain, store: FactStore, names: frozenset[str]) -> tuple[str, ...]:
    """The facts of ``store`` that name any of ``names``, as text, sorted: perceived ones
    only (not the planner's own predicates, not where the robot is, which every move
    changes)."""
    skip = set(dom.model_preds)
    if dom.travel is not None:
        skip.add(dom.travel.location.pred)
    out = set()
    for pred, rows in store.facts.items():
        if not isinstance(pred, str) or pred in skip:
            continue
        out.update(str(Literal(pred, args)) for args in rows
                   if any(a in names for a in args))
    return tuple(sorted(out))


def exclude(dom: Domain, step: PlanStep, before: tuple[str, ...], store: FactStore,
            cycle: int) -> Exclusion:
    """The exclusion a step that did not achieve its primary effect leaves behind."""
    after = perceived_about(dom, store, objects(step))
    depends = tuple(f for f in after if f not in set(before))
    why = f"{step.primary} did not hold after it" + (
        f", {' '.join(depends)} observed" if depends else "")
    return Exclusion(step.text, step.achieves, cycle, why, depends)


def lapsed(x: Exclusion, holds) -> str:
    """Why a standing exclusion no longer stands ("" while it does); ``holds`` tells whether
    a literal (text) holds now."""
    gone = next((f for f in x.depends if not holds(f)), None)
    if gone is not None:
        return f"{gone} no longer holds"
    if not x.depends and holds(x.achieves):
        return f"{x.achieves} holds now"
    return ""


def reopen(t: Task, holds, cycle: int, events: list[str]) -> Task:
    """``t`` with the exclusions whose situation changed opened again; its tail-plan is then
    made afresh (the choice it was made without is open)."""
    if not t.standing():
        return t
    out, opened = [], []
    for x in t.excluded:
        why = lapsed(x, holds) if x.standing else ""
        if why:
            x = replace(x, opened=cycle, reopened=why)
            opened.append(x)
            events.append(f"cycle {cycle}: {t.goal_id} {x.step} for {x.achieves} open again: "
                          f"{why}")
        out.append(x)
    if not opened:
        return t
    note = "; ".join(f"{x.step} open again ({x.reopened})" for x in opened)
    return replace(t, excluded=tuple(out), replan=t.replan or note)


def excluded_here(excluded: tuple[Exclusion, ...], goal: str, step_text: str
                  ) -> Exclusion | None:
    """The standing exclusion of operator instance ``step_text`` for ``goal``, if any."""
    return next((x for x in excluded if x.standing and x.achieves == goal
                 and x.step == step_text), None)
