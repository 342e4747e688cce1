"""Loose variables: a skill's variable that its head leaves open and that one
condition of its start names beside static ones, which name it too, such as elevators' count of
passengers ``?n1`` of boarding, in ``(passengers ?lift ?n1)`` and ``(next ?n1 ?n2)``. Any value
that makes that condition hold will do, so the condition is *incidental*: a chosen way whose
incidental condition has become false is bound afresh to the values that hold now (``rebind``,
agents/lang/solving/search.py) rather than pushing it as a subgoal (the count the lift had
when the way was chosen, which only a detour of boarding and leaving would restore). Pure."""

from __future__ import annotations

from dataclasses import replace
from itertools import islice

from ..core.matcher import solve
from ..core.terms import Literal, Var
from ..execution.paths import btuple
from .learner import static
from .state import SKILL, Alternative, StackEntry, grounded
from .task import Task

MAX_REBIND = 64     # bindings of a way's loose variables examined when binding it afresh


def loose_vars(task: Task, number: int) -> frozenset[Var]:
    """The variables of skill ``number`` that its head leaves open and that exactly one
    positive condition of its start names beside static ones, which name it too but do not
    tie it to the head's variables alone (elevators' count ``?n1`` of boarding, named by
    ``(passengers ?lift ?n1)`` and the static ``(next ?n1 ?n2)``; not miconic's floor of
    boarding, which ``(origin ?p ?f)`` fixes, nor the block B is on when it is unstacked,
    which no static condition names): any value that makes that condition hold will do."""
    return _roles(task, number)[0]


def rebound_vars(task: Task, number: int) -> frozenset[Var]:
    """The loose variables of skill ``number`` (``loose_vars``) and those the head leaves
    open that only static conditions name beside one of them (the ``?n2`` of boarding's
    ``(next ?n1 ?n2)``): the variables bound afresh when an incidental condition fails."""
    return _roles(task, number)[1]


def _roles(task: Task, number: int) -> tuple[frozenset[Var], frozenset[Var]]:
    """(``loose_vars``, ``rebound_vars``) of skill ``number``, kept for the cycle."""
    key = ("loose", number)
    if key not in task.memo:
        s = task.skill(number)
        head = set(s.head.variables())
        conds = [c for c in (*s.start, *s.requires) if isinstance(c, Literal)]
        fixed = [c for c in conds if static(task, str(c)) and not _effect(task, c.pred)]
        fluent = [c for c in conds if c not in fixed]

        def count(v: Var) -> int:
            return 99 if any(o.negated and v in o.variables() for o in fluent) else \
                sum(v in o.variables() for o in fluent)

        open_ = {v for c in conds for v in c.variables() if v not in head and count(v) <= 1}
        pinned = {v for c in fixed for v in c.variables() if set(c.variables()) - {v} <= head}
        free = frozenset(v for v in open_ - pinned if count(v) == 1 and
                         any(v in c.variables() for c in fixed))
        more = {v for c in fixed if free & set(c.variables())
                for v in c.variables() if v in open_ and count(v) == 0}
        task.memo[key] = (free, free | more)
    return task.memo[key]


def _effect(task: Task, pred: str) -> bool:
    """Whether a skill's stated effects change ``pred`` (a count no skill is written for
    is still no static relation)."""
    return any(e.pred == pred for s in task.program.skills for e in s.effects)


def loose(task: Task, way) -> frozenset[int]:
    """The indices of the incidental conditions of the skill way ``way``: the positive
    conditions that name a loose variable (``loose_vars``)."""
    if way.kind != SKILL:
        return frozenset()
    free = loose_vars(task, way.clause)
    if not free:
        return frozenset()
    s = task.skill(way.clause)
    return frozenset(i for i, c in enumerate((*s.start, *s.requires))
                     if isinstance(c, Literal) and not c.negated and free & set(c.variables()))


def rebind(task: Task, entry: StackEntry) -> StackEntry:
    """``entry`` with its chosen skill way bound afresh where an incidental condition of it
    does not hold (``loose``): each group of rebound variables (``rebound_vars``) that the
    conditions tie together and whose incidental conditions do not all hold takes the first
    values that make them hold now, the rest of the binding kept (the count of passengers a
    lift has now, not the one it had when the way was chosen; freecell's free columns now,
    while which card must be home first stays). Unchanged where no group can."""
    way = entry.decision
    idx = loose(task, way) if way is not None else frozenset()
    if not idx or all(task.holds(way.conditions[i]) for i in idx):
        return entry
    s = task.skill(way.clause)
    conds = [*s.start, *s.requires]
    b = {Var(k): v for k, v in way.bindings}
    changed = False
    for group in _groups(conds, {v.name for v in rebound_vars(task, way.clause)}):
        named = [c for c in conds if {v.name for v in c.variables()} & group]
        if all(task.holds(c) for c in grounded(named, b) or ()):
            continue
        keep = {k: v for k, v in b.items() if k.name not in group}
        for nb in islice(solve([*s.percepts, *named], keep, task.pidx, task.store),
                         MAX_REBIND):
            if grounded(conds, nb) is not None and not task.undoes_skill(s, nb):
                b, changed = nb, True
                break
    if not changed:
        return entry
    new = Alternative(SKILL, way.clause, way.name, btuple(b),
                      tuple(map(str, grounded(conds, b))), task._shows(s, b))
    alts = list(entry.alternatives)
    alts[entry.chosen] = new
    held = tuple(c for c in new.conditions if task.holds(c) and c not in entry.initial)
    return replace(entry, alternatives=tuple(alts), initial=entry.initial + held)


def _groups(conds: list, names: set[str]) -> list[set[str]]:
    """The variables ``names`` in groups that one of ``conds`` names together."""
    groups: list[set[str]] = []
    for c in conds:
        mine = {v.name for v in c.variables()} & names
        if not mine:
            continue
        joined = [g for g in groups if g & mine]
        groups = [g for g in groups if not g & mine] + [mine.union(*joined)]
    return groups
