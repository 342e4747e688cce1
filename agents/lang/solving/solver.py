"""The means-ends problem solver as the executive's impasse handler (seed 000, "Problem Solving
and Skill Learning"; agents/lang/execution/executive.py, ImpasseHandler).

Every cycle, before the goal walk (``begin``), each goal stack is brought up to date: what the
conditions of each chosen way did since (achieved, lost, achieved again) is recorded; the
lowest entry that holds now is popped with everything above it, and each popped entry that
holds teaches a skill (agents/lang/solving/learner.py), added to EngineState.learned and used
from the next cycle on. A stack whose goal was removed is dropped. When the walk reaches a goal
with no executable path (``solve``), its stack (a new one if none) takes one cycle of search
(agents/lang/solving/search.py).

Priorities: problem solving runs only for the first unsatisfied goal the walk reaches in
impasse; a violated higher goal takes the cycle first. The stack of a pre-empted goal is
**kept and resumed**, not rebuilt: it is brought up to date every cycle like any other (what
the higher goal's actions achieve is popped and learned from, what they undo is noted as
lost), and solving continues from its top when the goal is reached again.
"""

from __future__ import annotations

from dataclasses import replace

from ..core.conjunction import Conjunction
from ..core.terms import Literal
from ..execution.effects import Effects
from ..execution.executive import Impasse, ImpasseHandler
from ..execution.paths import NOTHING, PathFinder, Remembered, Walk
from ..reading.goals import GoalEntry
from .landmarks import (
    excused,
    held_by,
    needs,
    one_step,
    pending_part,
    protected_landmark,
    undoes_any,
)
from .learner import canonical, learn
from .ordering import agenda
from .search import MAX_PUSHES, advance, focus, keeping, next_push
from .section import SolverSection
from .state import CONCEPT, CONJUNCTION, GoalStack, SolverState, StackEntry, literal, pushable
from .task import Task
from .typed import TypedEffects


class MeansEndsSolver(ImpasseHandler):
    """Stateless: everything it keeps between cycles is in EngineState.solver (goal stacks)
    and EngineState.learned (learned skills), so one instance serves every agent (within a
    cycle it keeps the Task of each goal, so that the executive's agenda and the search share
    their regressions)."""

    def __init__(self) -> None:
        self._walk: Walk | None = None
        self._tasks: dict[str, Task] = {}
        self._shared: dict = {}   # agendas by situation (agents/lang/solving/ordering.py)

    def task(self, finder: PathFinder, walk: Walk, goal_id: str = "") -> Task:
        """This cycle's Task for goal ``goal_id`` (the goals before it protected)."""
        if self._walk is not walk:
            self._walk, self._tasks = walk, {}
            self._effects(finder).see(walk.pidx, walk.store)
        task = self._tasks.get(goal_id)
        if task is None or task.program is not finder.program:
            effects = self._effects(finder)
            task = Task(finder.program, walk.pidx, walk.store, tuple(walk.protected),
                        effects, self._shared, _undone(effects, walk))
            self._tasks[goal_id] = task
        return task

    def _effects(self, finder: PathFinder) -> Effects:
        """The effect model the solver orders its choices by: the program's, with what a
        STRIPS-like program's starts imply (agents/lang/solving/relaxed.py), kept while the
        program is the same."""
        hit = self._shared.get(("effects", id(finder.program)))
        if hit is None or hit.program is not finder.program:
            hit = TypedEffects(finder.program, finder.effects)
            self._shared[("effects", id(finder.program))] = hit
        return hit

    def agenda(self, finder: PathFinder, walk: Walk, entry: GoalEntry,
               conj: Conjunction | Literal, current: str) -> list[Literal]:
        """The conjuncts of ``conj`` (or the relations of the concept definition the goal
        ``conj`` is decomposed through) the executive may pursue now, best first: while the
        agenda still has the one this goal's stack works on (or, without a stack, the one its
        path was for: ``current``), the conjuncts one action achieves now, then that one;
        otherwise the whole agenda (agents/lang/solving/ordering.py). A conjunct the stack
        works on that the agenda no longer has (another conjunct's plan needs what it would
        undo) is dropped from the stack, to be chosen afresh; a part of a plan it works on
        first (a promoted need) is kept while unsatisfied: the plan still needs it."""
        task = self.task(finder, walk, entry.id)
        ways = [w for w in task.alternatives(conj)
                if isinstance(conj, Conjunction) or w.kind == CONCEPT]
        if not ways:
            return []
        stack = walk.current("solver").stack_of(entry.id)
        mine = stack is not None and stack.entries[0].goal == str(conj)
        conds = ways[0].conditions
        if mine:
            current = stack.entries[1].goal if len(stack.entries) > 1 else ""
            chosen = stack.entries[0].decision   # the binding the search works on (issue
            if chosen is not None:               # 31: not a new best one each cycle)
                conds = chosen.conditions
        items = agenda(task, conds, current)
        if current and current in items:   # in passing: a conjunct one action achieves (a
            # block in the hand to its place); not a part of another's plan, which would
            # take the hand from the work under way, nor one that undoes what the way under
            # way has already achieved (a car rotated back off the segment it was brought to)
            held = held_by(task, stack) if mine else [   # (no stack: what the path's plan
                n for n in needs(task, current) if pushable(n) and task.holds(n)]   # holds)
            items = list(dict.fromkeys([c for c in items if c in conds and one_step(task, c)
                                        and not undoes_any(task, c, held)] + [current]))
        elif current and mine and (current in conds or not items) and \
                not self._refocus(task, walk, stack, conds, current):
            items = [current]   # (a part of a plan done first stays: the plan needs it)
        elif current and not mine and pending_part(task, conds, current):
            items = [current, *items]   # so does one the executive's own path was for (a
            # learned skill clearing B: the hand it filled on the way no longer makes the
            # agenda promote (clear B), which the solver's stack would still work on)
        elif current and not mine and items and current not in conds and \
                items[0] in conds and task.holds(current) and \
                literal(current) in needs(task, items[0]):
            items = items[:1]   # a part of a plan just done: that plan goes on (to an
            # impasse if no path goes on with it), not another conjunct's path from there
        return [literal(c) for c in items]

    def possible(self, finder: PathFinder, walk: Walk, inst: Literal) -> bool:
        """False when no skill or concept can make the goal instance ``inst`` true
        (``(on D D)`` among ``(on D ?x)``'s; agents/lang/solving/bindings.py): the executive
        leaves it out of the goal's instances."""
        return self.task(finder, walk).reach.possible(inst)

    def loop(self, finder: PathFinder, walk: Walk, entry: GoalEntry, reason: str) -> bool:
        """Back off after a circle (agents/lang/execution/loops.py): the top of the goal's stack
        fails with ``reason``, its parent's way given up as after any failed subgoal (under a
        conjunction: that conjunct is not pushed again). False when there is no stack."""
        state: SolverState = walk.current("solver")
        stack = state.stack_of(entry.id)
        if stack is None:
            return False
        entries = list(stack.entries)
        top = entries.pop() if len(entries) > 1 else entries[0]
        if not entries:
            entries = [top.give_up(reason)]
        elif entries[-1].decision is not None and entries[-1].decision.kind == CONJUNCTION:
            parent = entries[-1]
            entries[-1] = replace(parent, pushes=parent.pushes + (top.goal,) * MAX_PUSHES)
        else:
            entries[-1] = entries[-1].give_up(f"its subgoal {top.goal}: {reason}")
        stacks = tuple(replace(stack, entries=tuple(entries)) if s.goal_id == entry.id else s
                       for s in state.stacks)
        _publish(walk, stacks, (f"{entry.id}: backtracked from {top.goal}: {reason}",), (), ())
        return True

    @staticmethod
    def _refocus(task: Task, walk: Walk, stack: GoalStack, conds: tuple[str, ...],
                 current: str) -> bool:
        """Drop what the stack of a conjunction does for ``current``, unless the search's next
        decision (``next_push``, with its focus) would push it again at once (a livelock) or
        its way excuses its threats. Dropped: True."""
        bottom = stack.entries[0]
        pushes = list(bottom.pushes)
        if current in pushes:
            del pushes[len(pushes) - 1 - pushes[::-1].index(current)]
        kept = replace(stack, entries=(replace(bottom, pushes=tuple(pushes)),))
        if next_push(task, kept.entries[0], [bottom.goal], focus(walk, stack.goal_id)) == \
                current:
            return False
        if excused(task, conds, current, stack):
            return False
        state: SolverState = walk.current("solver")
        stacks = tuple(kept if s.goal_id == stack.goal_id else s for s in state.stacks)
        _publish(walk, stacks, (f"{stack.goal_id}: dropped {current}: achieving it now would "
                                "undo what another conjunct's plan needs",), (), ())
        return True

    def begin(self, finder: PathFinder, walk: Walk) -> None:
        state: SolverState = walk.current("solver")
        if not state.stacks:
            return
        task = self.task(finder, walk)
        live = {e.id for e in walk.state.goals}
        known = _known(finder)
        stacks, events, learned = [], [], []
        for stack in state.stacks:
            if stack.goal_id not in live:
                events.append(f"{stack.goal_id}: goal removed: its goal stack is dropped")
                continue
            stack = replace(stack, entries=tuple(_observe(task, e) for e in stack.entries))
            stack, ev, new = _settle(task, stack, walk.state.cycle, known)
            events += [f"{stack.goal_id}: {e}" for e in ev]
            learned += new
            if stack.entries:
                stacks.append(stack)
        _publish(walk, tuple(stacks), tuple(events), (), tuple(learned))

    def solve(self, finder: PathFinder, walk: Walk, entry: GoalEntry,
              unsatisfied: list[Literal]) -> Impasse:
        state: SolverState = walk.current("solver")
        stack = state.stack_of(entry.id)
        insts = [str(u) for u in unsatisfied]
        events: list[str] = []
        task = self.task(finder, walk, entry.id)
        if stack is None or stack.entries[0].goal not in insts:
            clash = protected_landmark(task, unsatisfied[0])
            if clash:   # seed 000: a lower goal may not undo a higher one; no way round it
                why = f"{insts[0]} cannot be achieved without undoing {clash}"
                _publish(walk, tuple(s for s in state.stacks if s.goal_id != entry.id),
                         (f"{entry.id}: failed: {why}",), (entry.id,), ())
                return Impasse(failed=why)
            stack = GoalStack(entry.id, (StackEntry(insts[0], f"goal {entry.id} in impasse"),),
                              walk.state.cycle)
            events.append(f"{entry.id}: impasse on {insts[0]}: problem solving begins")
        elif len(stack.entries) > 1 and stack.entries[0].decision is not None and \
                stack.entries[0].decision.kind == CONCEPT:   # a goal written as a concept:
            self.agenda(finder, walk, entry, unsatisfied[0], "")   # its relations as (and)'s
            stack = walk.current("solver").stack_of(entry.id) or stack
        prev = walk.state.path_of(entry.id)

        def probe(goal: Literal, keep: tuple[Literal, ...], made: tuple[Literal, ...]):
            memory = Remembered(prev, entry.id not in walk.state.active) \
                if prev and prev[0].goal == str(goal) else NOTHING
            found = finder.achieve(walk, goal, memory, 0, frozenset())
            return keeping(finder, walk, goal, keep, entry.id, found, made)

        step = advance(task, stack, probe, focus(walk, entry.id))
        events += [f"{entry.id}: {e}" for e in step.events]
        conflicts = tuple(dict.fromkeys(stack.conflicts + tuple(
            f"{g} {text}" for g, text in task.conflicts.items())))
        others = tuple(s for s in state.stacks if s.goal_id != entry.id)
        mine = (replace(step.stack, conflicts=conflicts),) if step.stack else ()
        stacks = tuple(sorted(others + mine, key=lambda s: s.goal_id))
        failed = step.failed
        if failed and conflicts:   # seed 000: a lower goal may not undo a higher one
            failed = (f"{insts[0]} cannot be achieved without undoing "
                      f"{' and '.join(conflicts)}, which "
                      f"{'holds' if len(conflicts) == 1 else 'hold'} and come"
                      f"{'s' if len(conflicts) == 1 else ''} first; {failed}")
        if failed:
            events.append(f"{entry.id}: failed: {failed}")
        _publish(walk, stacks, tuple(events), (entry.id,), ())
        return Impasse(step.found, failed, step.note)


def _observe(task: Task, e: StackEntry) -> StackEntry:
    """Record what the conditions of ``e``'s chosen way did since last cycle: one that
    became true (false at the choice, or lost since) goes to the end of ``order``; one that
    held and became false goes to ``lost``."""
    way = e.decision
    if way is None:
        return e
    order, lost = list(e.order), list(e.lost)
    for c in way.conditions:
        now = task.holds(c)
        if now and (c in lost or (c not in e.initial and c not in order)):
            lost = [x for x in lost if x != c]
            order = [x for x in order if x != c] + [c]
        elif not now and (c in e.initial or c in order) and c not in lost:
            lost.append(c)
    return replace(e, order=tuple(order), lost=tuple(lost))


def _settle(task: Task, stack: GoalStack, cycle: int, known: dict[str, str]
            ) -> tuple[GoalStack, list[str], list[str]]:
    """Pop the lowest entry that holds and everything above it, learning from each popped
    entry that holds. Returns (stack, events, clauses learned)."""
    entries = list(stack.entries)
    low = next((i for i, e in enumerate(entries) if task.holds(e.goal)), None)
    if low is None:
        return stack, [], []
    events, learned = [], []
    for k in range(len(entries) - 1, low - 1, -1):
        e = entries[k]
        if not task.holds(e.goal):
            events.append(f"dropped {e.goal}: {entries[low].goal} below it holds")
            continue
        way = e.decision
        how = "" if way is None else f"concept chaining on {way.name}" \
            if way.kind == "concept" else f"skill chaining off {way.shows}"
        comment = (f"learned at cycle {cycle} from problem {entries[0].goal} (goal "
                   f"{stack.goal_id}): {e.goal} by {how}")
        new = learn(task, e, comment, known)
        start: tuple[str, ...] | None = None
        if new is not None:
            start = new.start
            if new.duplicate:
                events.append(f"achieved {e.goal}: learned nothing new (same as "
                              f"{new.duplicate})")
            else:
                learned.append(new.text)
                events.append(f"achieved {e.goal}: learned skill {new.skill.head}")
        else:
            events.append(f"achieved {e.goal}")
            if e.done is not None:
                start = task.start_of(*e.done)
        if k > 0 and start is not None:
            parent = entries[k - 1]
            if e.goal not in dict(parent.starts):
                entries[k - 1] = replace(parent, starts=parent.starts + ((e.goal, start),))
    if low == 0:
        events.append(f"solved {entries[0].goal} (problem solving since cycle {stack.started})")
    return replace(stack, entries=tuple(entries[:low])), events, learned


def _known(finder: PathFinder) -> dict[str, str]:
    return {canonical(s): s.name for s in reversed(finder.program.skills)}


def _publish(walk: Walk, stacks: tuple[GoalStack, ...], events: tuple[str, ...],
             solving: tuple[str, ...], learned: tuple[str, ...]) -> None:
    """Write the solver's state for the next cycle (and new skills into EngineState.learned)
    and this cycle's section of the Decision (merged with what ``begin`` put there)."""
    walk.updates["solver"] = SolverState(stacks)
    old = next((s for s in walk.sections if s.name == "solver"), None)
    if learned:
        walk.updates["learned"] = tuple(walk.current("learned")) + learned
    if old is not None:
        walk.sections.remove(old)
        events, solving, learned = (old.events + events, old.solving + solving,
                                    old.learned + learned)
    if stacks or events or learned:
        walk.sections.append(SolverSection(stacks, events, solving, learned))


def _undone(effects: Effects, walk: Walk) -> tuple[Literal, ...]:
    """What the last cycle's done actions undid (ground patterns of the effect model)."""
    actions = [o.action for o in walk.outcomes if o.ok]
    if not actions:
        return ()
    return tuple(p for p in effects.of_actions(actions)[1] if not p.variables())
