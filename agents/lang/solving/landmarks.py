"""Landmarks: the conditions that every way of achieving a literal from the current
situation passes through, by goal regression over the program: each way (a primitive skill
whose head matches, a concept clause with :relations) counts with its conditions and what their
definitions consist of; the landmarks are what all ways share, and, for those that do not hold,
their own landmarks. ``(on B C)`` from the table needs ``(stackable B C)``, ``(clear C)``,
``(holding B)``, ``(clear B)`` and ``(hand-empty)``, whichever way B is lifted.

Used to tell a conjunct that must wait for another from one that merely gets in the way of how
the world happens to be (agents/lang/solving/ordering.py), and to leave out a way whose own
condition could only be reached through the goal it is for (agents/lang/solving/task.py).

The other regression of a goal lives here too: ``needs``, what the solver's own plan for it
needs (the first way at each level), and what threatens those needs (``threatens``: the
definition the agenda's index answers by), with the checks the solver makes with them on
its goal stack (``excused``, ``held_by``, ``undoes_any``, ``pending_part``).
``task`` is a Task (holds, program, memo); pure."""

from __future__ import annotations

from itertools import chain

from ..core.matcher import solve, unify_head
from ..core.terms import Literal, Test, Var
from ..execution.effects import undone_by
from .state import SKILL, condition, literal, pushable

MAX_LANDMARK = 6   # levels of landmark regression [levels]
MAX_PLAN = 80      # deepest regression of a conjunct's plan [levels]
MAX_SUPPORT = 2    # levels of what a holding subgoal holds by [levels]
MAX_REGRESS = 256   # literals regressed for one goal's needs [literals]: a goal reached by
                    # many ways through the same literals is regressed along each; the tuned
                    # domains' plans take a few dozen
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


def needs(task, goal: str, above: tuple[str, ...] = ()) -> dict[Literal, str]:
    """What the solver's plan for ``goal`` needs to hold at some point, each with the nearest
    unsatisfied goal above it in that plan ("" for ``goal`` itself); its ways go not through
    the goals ``above`` (depot's crate into the truck at the depot where it lies, not by a
    hoist at the distributor where it is to be lifted from the truck: that hoist lifting
    it is the goal the truck's unloading is for)."""
    key = ("needs", goal, above)
    if key not in task.memo:
        out: dict[Literal, str] = {}
        _regress(task, literal(goal), "", 0, frozenset(), out, frozenset(above),
                 [MAX_REGRESS])
        task.memo[key] = out
    return task.memo[key]


def _regress(task, goal: Literal, above: str, depth: int, on_path: frozenset,
             out: dict[Literal, str], avoid: frozenset, budget: list[int]) -> None:
    out.setdefault(goal, above)
    budget[0] -= 1
    if depth >= MAX_PLAN or goal in on_path or budget[0] < 0:
        return
    if task.holds(goal):
        for r in _support(task, goal, MAX_SUPPORT):
            out.setdefault(r, above)
        return
    ways = task.alternatives(goal, applicable=True)   # an executable skill is a way too,
    ways = sorted(ways, key=lambda w: (not all(task.holds(c) for c in w.conditions),  # first;
                                       _estimate(task, w)))   # then as the search ranks them
    path = {str(g) for g in on_path} | {str(goal)} | avoid   # not a way back through the
    # plan above, nor through the goals ``avoid`` above it on the stack
    ways = [w for w in ways if not path & set(w.conditions)] or ways   # (put F down to clear it)
    if not ways:
        return
    here = str(goal)
    for c in ways[0].conditions:
        cond = condition(c)
        if isinstance(cond, Test):
            continue
        if cond.negated or cond.variables():
            out.setdefault(cond, here)
        else:
            _regress(task, cond, here, depth + 1, on_path | {goal}, out, avoid, budget)


def _estimate(task, way) -> float:
    """The relaxed distance of ``way``'s conditions (Task.estimate; 0 where the program
    admits none): the regression follows the way the search would choose (an airplane
    pushed back to the taxiway it is to start up on, not moved there under its own power)."""
    if not task.estimated():
        return 0
    est = task.estimate([condition(c) for c in way.conditions])
    return 0 if est is None else est


def _support(task, goal: Literal, depth: int) -> list[Literal]:
    """What the holding literal ``goal`` holds by: the relations of its first clause that
    holds, ground where its solution binds them (negations keep their open variables)."""
    if depth <= 0:
        return []
    for clause in task.program.concepts.get(goal.pred, ()):
        if not clause.relations:
            continue
        b0 = unify_head(clause.head, goal, {})
        if b0 is None:
            continue
        sol = next(solve([*clause.percepts, *clause.relations, *clause.tests], b0, task.pidx,
                         task.store), None)
        if sol is None:
            continue
        out = []
        for r in clause.relations:
            g = Literal(r.pred, tuple(sol.get(a, a) if isinstance(a, Var) else a
                                      for a in r.args), r.negated)
            out.append(g)
            if not g.negated and not g.variables():
                out += _support(task, g, depth - 1)
        return out
    return []


def threatens(task, g: str, need: Literal, above: str = "") -> bool:
    """True when achieving the conjunct ``g`` makes ``need`` false, unless it also achieves
    ``above``, the goal ``need`` is needed for (a program stating its skills' effects:
    stacking B, held to be put down to clear it, on A clears it as well)."""
    lit = literal(g)
    if need.negated:
        return undone_by(lit, (Literal(need.pred, need.args),))
    if need.variables() or not undone_by(need, task.effects.undoes(lit)):
        return False
    return not (above and undone_by(literal(above), tuple(task.effects.achieved_with(lit))))


def excused(task, conds: tuple[str, ...], g: str, stack) -> bool:
    """Whether the way under way for the conjunct ``g`` (the skill chained off it on the goal
    stack ``stack``) excuses every threat of ``g`` to another unsatisfied conjunct's plan:
    each is to a need that plan has only for a goal the way achieves too (a piece glazed
    white is glazed, so its being untreated, which glazing it black would need, is no longer
    needed). False when there is no threat, or no such way."""
    way = stack.entries[1].decision if len(stack.entries) > 1 else None
    if way is None or way.kind != SKILL or g not in conds:
        return False
    made = made_by(task, way)
    unsat = [c for c in conds if c != g and pushable(condition(c)) and not task.holds(c)]
    threats = [above for h in unsat for need, above in needs(task, h).items()
               if threatens(task, g, need, above)]
    return bool(threats) and all(above and literal(above) in made for above in threats)


def made_by(task, way) -> list[Literal]:
    """The ground literals the skill of the way ``way`` (an Alternative) states it achieves."""
    s = task.skill(way.clause)
    b = dict(way.bindings)
    return [Literal(x.pred, tuple(b.get(a.name, a) if isinstance(a, Var) else a
                                  for a in x.args))
            for x in (s.head, *s.effects) if not x.negated]


def held_by(task, stack) -> list[Literal]:
    """The conditions of the ways chosen above the bottom of the goal stack ``stack`` that
    hold now: what the work under way has achieved, or found, and still needs."""
    return [literal(c) for e in stack.entries[1:] if e.decision is not None
            for c in e.decision.conditions if pushable(condition(c)) and task.holds(c)]


def undoes_any(task, goal: str, held: list[Literal]) -> bool:
    """Whether achieving ``goal`` makes one of ``held`` false (the program's effects)."""
    if not held:
        return False
    patterns = task.effects.undoes(literal(goal))
    return any(undone_by(h, patterns) for h in held)


def pending_part(task, conds: tuple[str, ...], goal: str) -> bool:
    """Whether ``goal`` is an unsatisfied part (not a conjunct) of the plan of an unsatisfied
    conjunct among ``conds`` (``needs``): the executive goes on with its own path for it."""
    if goal in conds or task.holds(goal) or not pushable(condition(goal)):
        return False
    return any(literal(goal) in needs(task, c) for c in conds
               if pushable(condition(c)) and not task.holds(c))


def plan_depth(plan: dict[Literal, str], need: Literal) -> int:
    """How many unsatisfied goals of ``plan`` (``needs``) lie between ``need`` and the
    conjunct the plan is for: (clear B), which unstacking B for (on B D) needs, is nearer
    (on B D) than (on A E), whose plan unstacks B off A to free A."""
    depth, above = 0, plan.get(need, "")
    while above and depth < MAX_PLAN:
        depth, above = depth + 1, plan.get(literal(above), "")
    return depth


def one_step(task, g: str) -> bool:
    """True when one executable primitive skill achieves ``g`` now (its start holds and it
    undoes no protected goal)."""
    lit = literal(g)
    for s in task.program.skills_for(lit.pred):
        if s.kind != "primitive":
            continue
        b0 = unify_head(s.head, lit, {})
        if b0 is None:
            continue
        for b in solve([*s.percepts, *s.start, *s.requires], b0, task.pidx, task.store):
            if not task.undoes_skill(s, b):
                return True
    return False
