"""Steps of a body that can never run because an earlier ``(assert FACT)`` makes the body's
goal true. A body serves its goal: from the cycle after the assert the goal
holds and the executive ends the body (runner.py ``end``, "bodies ended: goal achieved"),
as seed 002's goals are "world states that the system is trying to achieve". In the assert's
own cycle the body goes on up to its next action; every step after that is cut off.
``teleo check`` names those steps in a warning (docs/language.md, SCS)."""

from __future__ import annotations

from ..core.program import Skill
from ..core.terms import Literal, Var
from .syntax import Act, Atomic, Construct, Kind, ModelUpdate, children, node_at, walk_steps


def achieves(fact: Literal, head: Literal) -> bool:
    """Whether asserting ``fact`` can make ``head`` true (same predicate and arity, and
    every argument pair equal or a variable on either side)."""
    return (fact.pred == head.pred and not fact.negated and not head.negated
            and len(fact.args) == len(head.args)
            and all(a == b or isinstance(a, Var) or isinstance(b, Var)
                    for a, b in zip(fact.args, head.args, strict=True)))


def cut_off(skill: Skill) -> list[tuple[ModelUpdate, list[object]]]:
    """For each assert in ``skill``'s body that achieves its head: the steps after it that
    never run (empty lists left out)."""
    out: list[tuple[ModelUpdate, list[object]]] = []
    if skill.body is None:
        return out
    for at, node in walk_steps(skill.body):
        parts = node.steps if isinstance(node, Atomic) else (node,)
        hits = [p for p in parts if isinstance(p, ModelUpdate) and not p.retract
                and achieves(p.fact, skill.head)]
        if not hits:
            continue
        spent = isinstance(node, Atomic) and any(isinstance(p, Act) for p in node.steps)
        after = _after(skill.body, at)
        never = after if spent else after[1:]   # the first one runs in the assert's cycle
        while never and isinstance(never[0], ModelUpdate) and not spent:
            never = never[1:]   # updates before the next action run in that cycle too
        if never:
            out.append((hits[0], never))
    return out


def _after(root: object, at: tuple[int, ...]) -> list[object]:
    """The steps that follow the step at ``at`` once it ends, in order: its later siblings
    in each enclosing ``do`` (a do-first, do-best or do-any ends with its chosen step; do-all
    and repeat are left alone: what runs after them depends on the others)."""
    out: list[object] = []
    while at:
        parent = node_at(root, at[:-1])
        if not isinstance(parent, Construct) or parent.kind in (Kind.ALL, Kind.REPEAT):
            break
        if parent.kind is Kind.DO:
            out += list(children(parent)[at[-1] + 1:])
        at = at[:-1]
    return out
