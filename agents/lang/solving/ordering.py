"""The order in which a conjunctive goal's conjuncts are pursued, by goal regression
over the program: achieve first what achieving another conjunct would not undo.

For each unsatisfied conjunct h, ``needs`` regresses the solver's own plan from the current
situation (the first way ``Task.alternatives`` ranks at each level, as the search would choose
it; for a subgoal that holds, what it holds by), and ``landmarks`` the conditions that every
way of achieving h passes through. A conjunct g *threatens* h when achieving g would make one
of h's needs false (agents/lang/execution/effects.py: ``(on A B)`` makes ``(clear B)`` false). Then:

1. a conjunct that threatens nobody may be pursued (building a tower from its base: ``(on B
   C)`` before ``(on A B)``, since ``(on A B)`` would undo ``(clear B)``, which ``(on B C)``
   needs to pick B up); among them, one that one executable action achieves now comes first
   (a block in the hand goes straight to its place), then the one being worked on, then the
   written order;
2. if every one threatens another, and g's threats are to needs that are not landmarks (they
   come from how the world happens to be, not from what h is), the part of h's plan that needs
   the threatened condition is done first: the nearest unsatisfied goal above it in h's plan
   (the Sussman anomaly: C on A, goal (and (on A B) (on B C)): (on B C) would cover C, which
   (on A B)'s plan must clear to free A, so (clear A) comes first);
3. otherwise the unsatisfied conjuncts in written order (the search may then undo a conjunct for
   a while; the MAX_PUSHES rule and the loop watch keep that from going on for ever).

A part of a plan to be done first (2.) that one action achieves now is done now even when some
conjunct is free (B1 on B2, both to end on the table's side of things: lifting B1 off B2 first
lets B3 go straight onto it later).

Pure; regressions are kept for the cycle in ``Task.memo``, agendas across cycles by situation
(a cycle spent deciding leaves the situation as it was) in ``Task.shared``."""

from __future__ import annotations

from ..core.matcher import solve, unify_head
from ..core.terms import Literal, Test, Var
from ..execution.effects import undone_by
from .landmarks import key as _key
from .landmarks import landmarks
from .state import SKILL, condition, literal, pushable
from .task import Task

MAX_PLAN = 80      # deepest regression of a conjunct's plan [levels]
MAX_SUPPORT = 2    # levels of what a holding subgoal holds by [levels]
MAX_REGRESS = 256   # literals regressed for one goal's needs [literals]: a goal reached by
                    # many ways through the same literals is regressed along each; the tuned
                    # domains' plans take a few dozen
MAX_SHARED = 64    # agendas kept across cycles [agendas]


def agenda(task: Task, conds: tuple[str, ...], current: str = "",
           above: tuple[str, ...] = ()) -> list[str]:
    """The literals to pursue for a conjunction with ground ``conds``, best first (see the
    module docstring); ``current``: the one being worked on; ``above``: the goals on the
    stack above (a skill's start: its plans go no way back through them). Empty when
    nothing can be pushed (every conjunct holds, or one that does not is a negation or a
    test)."""
    key = ("agenda", task.situation, conds, current, task.protected, above)
    if key in task.shared:
        return task.shared[key]
    unsat = [c for c in conds if pushable(condition(c)) and not task.holds(c)]
    plans = {h: needs(task, h, above) for h in unsat}
    free, promote = [], []
    # achieving a conjunct that another undoes outright is left for after it (the movie is
    # rewound, which resets the counter, before the counter is reset); the one that undoes it
    # is not held back for that (achieving it first is the way round)
    later = {h for h in unsat if any(g != h and _threatens(task, g, literal(h), "")
                                     for g in unsat)}
    for g in unsat:
        threats = [(h, need, above) for h in unsat if h != g
                   for need, above in plans[h].items() if _threatens(task, g, need, above)
                   and not (h in later and need == literal(h) and not above)]
        if not threats:
            free.append(g)
        elif not any(_key(need) in landmarks(task, literal(h)) for h, need, _ in threats):
            promote += [above for _, _, above in threats if above]
    if current and current not in conds:   # a part of a conjunct's plan, done first: that
        # conjunct's plan goes on (not another's, which would move again what the
        # first would have put in its place): of those free, the one whose plan needs it
        # nearest
        current = min((h for h in [*free, *unsat] if literal(current) in plans[h]),
                      key=lambda h: (h not in free, _depth(plans[h], literal(current))),
                      default=current)
    if free:
        now = [g for g in free if one_step(task, g)]
        now += [p for p in dict.fromkeys(promote) if p not in now and one_step(task, p)]
        out = now + [g for g in free if g == current and g not in now] + \
            [g for g in free if g not in now and g != current]
        out = [g for g in out if g not in later] + [g for g in out if g in later]
    elif promote:
        out = list(dict.fromkeys(promote))
    else:
        out = unsat
    if len(task.shared) >= MAX_SHARED:
        task.shared.clear()
    task.shared[key] = out
    return out


def _depth(plan: dict[Literal, str], need: Literal) -> int:
    """How many unsatisfied goals of ``plan`` (``needs``) lie between ``need`` and the
    conjunct the plan is for: (clear B), which unstacking B for (on B D) needs, is nearer
    (on B D) than (on A E), whose plan unstacks B off A to free A."""
    depth, above = 0, plan.get(need, "")
    while above and depth < MAX_PLAN:
        depth, above = depth + 1, plan.get(literal(above), "")
    return depth


def needs(task: Task, goal: str, above: tuple[str, ...] = ()) -> dict[Literal, str]:
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


def _regress(task: Task, goal: Literal, above: str, depth: int, on_path: frozenset,
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


def _estimate(task: Task, way) -> float:
    """The relaxed distance of ``way``'s conditions (Task.estimate; 0 where the program
    admits none): the regression follows the way the search would choose (an airplane
    pushed back to the taxiway it is to start up on, not moved there under its own power)."""
    if not task.estimated():
        return 0
    est = task.estimate([condition(c) for c in way.conditions])
    return 0 if est is None else est


def _support(task: Task, goal: Literal, depth: int) -> list[Literal]:
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


def _threatens(task: Task, g: str, need: Literal, above: str = "") -> bool:
    """True when achieving the conjunct ``g`` makes ``need`` false, unless it also achieves
    ``above``, the goal ``need`` is needed for (a program stating its skills' effects:
    stacking B, held to be put down to clear it, on A clears it as well)."""
    lit = literal(g)
    if need.negated:
        return undone_by(lit, (Literal(need.pred, need.args),))
    if need.variables() or not undone_by(need, task.effects.undoes(lit)):
        return False
    return not (above and undone_by(literal(above), tuple(task.effects.achieved_with(lit))))


def one_step(task: Task, g: str) -> bool:
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


def excused(task: Task, conds: tuple[str, ...], g: str, stack) -> bool:
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
               if _threatens(task, g, need, above)]
    return bool(threats) and all(above and literal(above) in made for above in threats)


def made_by(task: Task, way) -> list[Literal]:
    """The ground literals the skill of the way ``way`` (an Alternative) states it achieves."""
    s = task.skill(way.clause)
    b = dict(way.bindings)
    return [Literal(x.pred, tuple(b.get(a.name, a) if isinstance(a, Var) else a
                                  for a in x.args))
            for x in (s.head, *s.effects) if not x.negated]


def held_by(task: Task, stack) -> list[Literal]:
    """The conditions of the ways chosen above the bottom of the goal stack ``stack`` that
    hold now: what the work under way has achieved, or found, and still needs."""
    return [literal(c) for e in stack.entries[1:] if e.decision is not None
            for c in e.decision.conditions if pushable(condition(c)) and task.holds(c)]


def undoes_any(task: Task, goal: str, held: list[Literal]) -> bool:
    """Whether achieving ``goal`` makes one of ``held`` false (the program's effects)."""
    if not held:
        return False
    patterns = task.effects.undoes(literal(goal))
    return any(undone_by(h, patterns) for h in held)


def pending_part(task: Task, conds: tuple[str, ...], goal: str) -> bool:
    """Whether ``goal`` is an unsatisfied part (not a conjunct) of the plan of an unsatisfied
    conjunct among ``conds`` (``needs``): the executive goes on with its own path for it."""
    if goal in conds or task.holds(goal) or not pushable(condition(goal)):
        return False
    return any(literal(goal) in needs(task, c) for c in conds
               if pushable(condition(c)) and not task.holds(c))
