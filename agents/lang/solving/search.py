"""Means-ends search over a goal stack, one decision per cycle (seed 000, "Problem Solving and
Skill Learning", Figure 3).

``advance`` takes the goal stack as the cycle found it (achieved subgoals already popped) and
returns a ``Step``: a path to execute as soon as the top subgoal has one (interleaving problem
solving with execution), or the stack after one chaining decision, or a failure with its
reason. A decision pushes one unsatisfied condition of the chosen way to chain off the top
entry; a way that cannot go on (its next condition is already on the stack, or was achieved
MAX_PUSHES times and undone each time: a loop; the stack is MAX_STACK deep; its conditions
hold but the skill is still not executable; its subgoal failed, or its path ran MAX_EXECUTE
cycles in vain) is abandoned for the entry's next alternative, and an entry with none left is
popped, failing its parent's way in turn (backtracking). When the bottom entry, the goal,
runs out of alternatives, the problem has failed."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

from ..core.terms import Literal
from ..execution.effects import undone_by, undone_goal
from ..execution.paths import Found, PathFinder, Walk
from .loose import rebind
from .ordering import agenda
from .state import (
    CONCEPT,
    CONJUNCTION,
    SKILL,
    Alternative,
    GoalStack,
    StackEntry,
    condition,
    goal_of,
    literal,
    pushable,
)
from .task import Task

MAX_STACK = 64      # deepest goal stack [entries] (clearing the bottom of a tower of 30
                    # blocks pushes two entries per block above it)
MAX_EXECUTE = 50    # cycles a subgoal's path may run without achieving it [cycles]
MAX_PUSHES = 2      # times one condition of a way may be pushed (achieved, undone, again)

Probe = Callable[[Literal, tuple[Literal, ...], tuple[Literal, ...]], "Found | None"]
"""An executable path for a subgoal in the current situation, or None; given the literals to
keep, one whose first action undoes none of them when there is such a path."""


@dataclass(frozen=True, slots=True)
class Step:
    """The result of one cycle of search: ``stack`` (None once the problem failed), ``found``
    (a path to execute now), ``failed`` (why the goal cannot be achieved), ``events`` (what
    was done, for the explanation) and ``note`` (one line for the goal's report)."""

    stack: GoalStack | None
    found: Found | None = None
    failed: str = ""
    events: tuple[str, ...] = ()
    note: str = ""


def advance(task: Task, stack: GoalStack, probe: Probe, focus: str = "") -> Step:
    """One cycle of means-ends search on ``stack`` (see the module docstring); ``focus``: the
    goal the executive's last path was for (a conjunct, or a part of one's plan done first):
    among the conjuncts free to be pushed, that one's goes on."""
    entries = list(stack.entries)
    events: list[str] = []
    decided = False
    while True:
        top = entries[-1]
        # (the goal itself, at the bottom, is what the executive has just found no path for)
        found = probe(literal(top.goal), *_kept(task, entries)) if len(entries) > 1 \
            else None
        if found is not None and top.executed < MAX_EXECUTE:
            first = found[2][0]
            entries[-1] = replace(top, executed=top.executed + 1,
                                  done=(first.skill, first.bindings))
            events.append(f"executing {top.goal} by {first.skill_name}")
            return Step(replace(stack, entries=tuple(entries)), found, "", tuple(events),
                        f"problem solving: executing {top.goal}")
        if found is not None:
            reason = f"its path ran {MAX_EXECUTE} cycles without achieving it"
        elif decided:
            return Step(replace(stack, entries=tuple(entries)), None, "", tuple(events),
                        f"problem solving: pushed {top.goal}")
        else:
            entry, child, reason = decide(task, top, [e.goal for e in entries], focus=focus)
            entries[-1] = entry
            if child is not None:
                entries.append(child)
                events.append(f"pushed {child.goal}: {child.why}")
                decided = True
                continue
        events.append(f"backtracked: {top.goal} cannot be achieved: {reason}")
        entries.pop()
        if not entries:
            return Step(None, failed=f"{top.goal} cannot be achieved: {reason}",
                        events=tuple(events))
        entries[-1] = entries[-1].give_up(f"its subgoal {top.goal} cannot be achieved: "
                                          f"{_short(reason)}")


def decide(task: Task, entry: StackEntry, on_stack: list[str], ready: bool = False,
           focus: str = "") -> tuple[StackEntry, StackEntry | None, str]:
    """One chaining decision for ``entry``: (entry updated, the child to push, "") or, when
    no way is left, (entry, None, why): the chosen way goes on with its next unsatisfied
    condition; failing that, the next alternative is chosen afresh. With ``ready`` (the
    planner's back-chainer, agents/lang/planning/backchain.py), a chosen way whose
    conditions all hold is answered (entry, None, ""): apply it."""
    if not entry.alternatives and entry.chosen == -1 and entry.tried == 0:
        entry = replace(entry, alternatives=task.alternatives(goal_of(entry.goal)))
        if not entry.alternatives:
            return entry, None, task.nothing_to_chain(entry.goal)
    while True:
        if entry.chosen == -1:
            if entry.tried >= len(entry.alternatives):
                return entry, None, "every alternative failed (" + \
                    "; ".join(entry.failures) + ")"
            way = entry.alternatives[entry.tried]
            entry = entry.choose(entry.tried, tuple(c for c in way.conditions
                                                     if task.holds(c)))
        entry = rebind(task, entry)
        if ready and all(task.holds(c) for c in entry.decision.conditions):
            return entry, None, ""
        child, why = _push(task, entry, entry.decision, on_stack, not ready, focus)
        if child is not None:
            return replace(entry, pushes=entry.pushes + (child.goal,)), child, ""
        entry = entry.give_up(why)


def _push(task: Task, entry: StackEntry, way: Alternative, on_stack: list[str],
          ordered: bool = True, focus: str = "") -> tuple[StackEntry | None, str]:
    """The next unsatisfied condition of ``way`` as a new stack entry, or why there is none;
    for a conjunction, or the concept definition of the goal itself (at the bottom of the
    stack), the first of its agenda (agents/lang/solving/ordering.py); with ``ordered`` (the
    solver; not the planner's back-chainer, whose control rules order its goals), also for a
    skill's start."""
    if way.kind == CONJUNCTION or (way.kind == CONCEPT and len(on_stack) == 1):
        cond = next_conjunct(task, way.conditions, entry.pushes, on_stack, focus)
    else:
        cond = next((c for c in way.conditions if not task.holds(c)), None)
        if ordered and way.kind == SKILL and cond is not None and \
                sum(not task.holds(c) for c in way.conditions) > 1:
            # a skill's start as a conjunction: achieve first what achieving another of its
            # conditions would not undo (the package into the truck before the truck to
            # where it is unloaded), as the agenda orders conjuncts
            items = [c for c in agenda(task, way.conditions, above=(entry.goal,))
                     if c in way.conditions and
                     c not in on_stack and entry.pushes.count(c) < MAX_PUSHES]
            cond = items[0] if items else cond
    if cond is None:
        return None, ("its start holds but it is still not executable" if way.kind == SKILL
                      else "every subconcept holds but the goal does not")
    if not pushable(condition(cond)):
        return None, f"{cond} does not hold and cannot become a subgoal"
    if cond in on_stack:
        return None, f"loop: {cond} is already on the goal stack"
    if entry.pushes.count(cond) >= MAX_PUSHES:
        others = " ".join(dict.fromkeys(c for c in entry.pushes if c != cond))
        return None, (f"loop: {cond} was achieved {MAX_PUSHES} times and undone each time "
                      f"while achieving {others or 'the rest'}")
    if len(on_stack) >= MAX_STACK:
        return None, f"depth bound: the goal stack already holds {MAX_STACK} (sub)goals"
    if way.kind == SKILL:
        why = f"chained off skill {way.shows} because its start {cond} is false"
    elif way.kind == CONJUNCTION:
        part = "a conjunct" if cond in way.conditions else \
            "needed first by the plan of a conjunct that another would otherwise undo"
        why = f"decomposed the conjunction; {cond} does not hold ({part})"
    else:
        why = (f"decomposed {entry.goal} through {way.shows} into "
               f"{' '.join(way.conditions)}; {cond} does not hold")
    return StackEntry(cond, why), ""


def _kept(task: Task, entries: list[StackEntry]
          ) -> tuple[tuple[Literal, ...], tuple[Literal, ...]]:
    """What a path for the top subgoal should not undo where it can help it: the conditions
    of the skills chained off on the stack below it that hold now (a hoist made available by
    putting its crate down anywhere but back on the crate a way below needs clear), less
    those that achieving it undoes whatever the way (the crate the hoist lifts); and the one
    of them the way right below achieved last, unless the top's own way needs it too (a hand
    emptied to unstack with): a one-action path undoing it goes back where that way began
    (``keeping``)."""
    top = entries[-1].goal
    undone = task.effects.undoes(literal(top))
    kept = tuple(dict.fromkeys(
        lit for e in entries[:-1] if e.decision is not None and e.decision.kind == SKILL
        for c in e.decision.conditions
        if c != top and pushable(lit := condition(c)) and task.holds(c)
        and not undone_by(lit, undone)))
    way, below = entries[-1].decision, entries[-2].decision
    last = set(entries[-2].order[-1:]) if below is not None and below.kind == SKILL \
        else set()
    return kept, tuple(lit for lit in kept if str(lit) in last - set(
        way.conditions if way is not None else ()))


def keeping(finder: PathFinder, walk: Walk, goal: Literal, keep: tuple[Literal, ...],
            goal_id: str, found: Found | None, made: tuple[Literal, ...] = ()
            ) -> Found | None:
    """``found`` (the first path for ``goal``), unless its actions undo one of ``keep`` (what
    the ways below the subgoal hold: ``_kept``) and a one-action path (a primitive skill whose
    head ``goal`` is) undoes none of them: then that one; with none, None when ``found`` is
    one action that undoes one of ``made`` (``_kept``: the crate dropped back on the crate
    just cleared), so that the search chains the subgoal instead. Only one-action paths are
    looked at, so that a subgoal with none costs one more pass over its primitive skills, not
    another search of every path."""
    if not found or not keep or not undone_goal(finder.effects, [("", "", keep)], found[1]):
        return found
    saved = walk.protected
    walk.protected = [*saved, (goal_id, f"(the ways below {goal})", keep)]
    try:
        for s in finder.program.skills_for(goal.pred):
            if s.kind == "primitive":
                other = finder.enter(walk, s, goal, str(goal), 0, frozenset())
                if other:
                    return other
    finally:
        walk.protected = saved
    if made and len(found[2]) == 1 and undone_goal(finder.effects, [("", "", made)], found[1]):
        return None
    return found


def next_conjunct(task: Task, conds: tuple[str, ...], pushes: tuple[str, ...],
                  on_stack: list[str], focus: str = "") -> str | None:
    """The conjunct of ``conds`` the search pushes next: the first of the agenda that is not
    on the stack nor pushed MAX_PUSHES times already (a conjunct given up after a circle is
    not pushed again); when the agenda has none left, the first that does not hold, in
    written order (a user's goal written as a concept is ordered as its relations written as
    (and ...) would be); ``focus``: the conjunct the executive's last path served."""
    items = [c for c in agenda(task, conds, focus) if c not in on_stack
             and pushes.count(c) < MAX_PUSHES]
    return items[0] if items else next((c for c in conds if not task.holds(c)), None)


def next_push(task: Task, entry: StackEntry, on_stack: list[str], focus: str = "") -> str | None:
    """The subgoal the search's next decision on ``entry`` pushes (``decide``, not committed),
    with the stack ``on_stack`` and the executive's ``focus`` (``advance``): what the solver's
    agenda asks before dropping a conjunct (would the search push it straight back?), so that
    its answer and the next push cannot differ. None when the decision pushes nothing."""
    child = decide(task, entry, on_stack, focus=focus)[1]
    return None if child is None else child.goal


def focus(walk: Walk, goal_id: str) -> str:
    """The goal the executive's last path for ``goal_id`` was for ("" when none): the focus
    the search pushes a conjunct by (``advance``), and the one the solver's ``_refocus``
    predicts with."""
    prev = walk.state.path_of(goal_id)
    return prev[0].goal if prev else ""


def _short(reason: str, limit: int = 400) -> str:
    """A nested reason, cut to ``limit`` characters (the full chain is in the events)."""
    return reason if len(reason) <= limit else reason[:limit - 3] + "..."

