"""Landmarks: the conditions that every way of achieving a literal from the current
situation passes through, by goal regression over the program: each way (a primitive skill
whose head matches, a concept clause with :relations) counts with its conditions and what their
definitions consist of; the landmarks are what all ways share, and, for those that do not hold,
their own landmarks. ``(on B C)`` from the table needs ``(stackable B C)``, ``(clear C)``,
``(holding B)``, ``(clear B)`` and ``(hand-empty)``, whichever way B is lifted.

Used to tell a conjunct that must wait for another from one that merely gets in the way of how
the world happens to be (agents/lang/solving/ordering.py), and to leave out a way whose own
condition could only be reached through the goal it is for (agents/lang/solving/task.py).
``task`` is a Task (holds, program, memo); pure."""

from __future__ import annotations

from itertools import chain

from ..core.matcher import unify_head
from ..core.terms import Literal, Var
from ..execution.effects import undone_by

MAX_LANDMARK = 6   # levels of landmark regression [levels]
_ANY = Var("_")


def landmarks(task, goal: Literal) -> frozenset[str]:
    """Keys (``key``) of the conditions that every way of achieving ``goal`` from the current
    situation passes through (see the module docstring); kept for the cycle in task.memo."""
    memo = ("landmarks", goal)
    if memo not in task.memo:
        task.memo[memo] = frozenset(_landmarks(task, goal, 0, frozenset()))
    return task.memo[memo]


def protected_landmark(task, goal) -> str:
    """Why ``goal`` cannot be achieved without undoing a protected goal (``task.protected``:
    the goals that hold and come first), or "": a landmark of it that does not hold and whose
    truth makes a literal of one false (``(on B28 B19)`` needs ``(clear B28)``, which undoes
    ``(on B4 B28)``). Every way passes through it, so no search can get round it."""
    if not task.protected or not isinstance(goal, Literal):
        return ""
    task.holds(goal)   # (a cheap way to have the task's caches warm; goal is false)
    for lm in _landmark_literals(task, goal):
        if lm.negated or lm.variables() or task.holds(lm):
            continue
        undone = task.effects.undoes(lm)
        for gid, text, lits in task.protected:
            hit = next((x for x in lits if not x.negated and undone_by(x, undone)), None)
            if hit is not None:
                return (f"{gid} {text}, which holds and comes first: every way to it needs "
                        f"{lm}, which would undo {hit}")
    return ""


def _landmark_literals(task, goal: Literal) -> list[Literal]:
    out: dict[str, Literal] = {}
    _collect(task, goal, 0, frozenset(), out)
    return list(out.values())


def _collect(task, goal: Literal, depth: int, seen: frozenset, out: dict) -> None:
    if depth >= MAX_LANDMARK or goal in seen or task.holds(goal):
        return
    ways = _ways(task, goal)
    if not ways:
        return
    common: dict[str, Literal] = dict(ways[0])
    for w in ways[1:]:
        common = {k: v for k, v in common.items() if k in w}
    out.update(common)
    for lit in common.values():
        if not lit.negated and not lit.variables():
            _collect(task, lit, depth + 1, seen | {goal}, out)


def _landmarks(task, goal: Literal, depth: int, seen: frozenset) -> set[str]:
    if depth >= MAX_LANDMARK or goal in seen or task.holds(goal):
        return set()
    ways = _ways(task, goal)
    if not ways:
        return set()
    common: dict[str, Literal] = dict(ways[0])
    for w in ways[1:]:
        common = {k: v for k, v in common.items() if k in w}
    out = set(common)
    for lit in common.values():
        if not lit.negated and not lit.variables():
            out |= _landmarks(task, lit, depth + 1, seen | {goal})
    return out


def _ways(task, goal: Literal) -> list[dict[str, Literal]]:
    """Each way to achieve ``goal`` (primitive skills, concept clauses) as the conditions it
    passes through, by key, variables the goal does not fix left open."""
    out = []
    for s in task.program.skills_for(goal.pred):
        b = unify_head(s.head, goal, {}) if s.kind == "primitive" else None
        if b is not None:
            conds = [c for c in chain(s.start, s.requires) if isinstance(c, Literal)]
            out.append(_expanded([_open(c, b) for c in conds], 2, task))
    for clause in task.program.concepts.get(goal.pred, ()):
        b = unify_head(clause.head, goal, {}) if clause.relations else None
        if b is not None:
            out.append(_expanded([_open(r, b) for r in clause.relations], 1, task))
    return [w for w in out if w]


def _expanded(lits: list[Literal], depth: int, task=None) -> dict[str, Literal]:
    """``lits`` and, ``depth`` levels down, the relations of the single-clause concepts they
    name (what holds whenever they hold), by key."""
    out = {key(x): x for x in lits}
    if depth <= 0 or task is None:
        return out
    for x in lits:
        clauses = task.program.concepts.get(x.pred, ()) if not x.negated else ()
        if len(clauses) == 1 and clauses[0].relations:
            b = unify_head(clauses[0].head, x, {})
            if b is not None:
                out.update(_expanded([_open(r, b) for r in clauses[0].relations], depth - 1,
                                     task))
    return out


def _open(lit: Literal, b: dict) -> Literal:
    return Literal(lit.pred, tuple(b.get(a, _ANY) if isinstance(a, Var) else a
                                   for a in lit.args), lit.negated)


def key(lit: Literal) -> str:
    """The text of ``lit`` with every variable written ``?_``."""
    return str(Literal(lit.pred, tuple(_ANY if isinstance(a, Var) else a for a in lit.args),
                       lit.negated))
