"""The executive (seed 000, "Inference and Execution Mechanisms", "Adding Goal Priorities").

Each cycle it walks the prioritized goal list; the first unsatisfied goal gets a skill path
(agents/lang/execution/paths.py: how a path is chosen). Achieved goals are rechecked every cycle
and a
violated higher goal suspends the current one, which later resumes its remembered path if
every skill on it could be started now, and chooses afresh otherwise. A path never takes an
action that the program says undoes a higher goal that holds (agents/lang/execution/effects.py). A
conjunctive goal is pursued one conjunct at a time, in the order of the impasse handler's
``agenda`` (agents/lang/core/conjunction.py). With a (resources ...) section, lower goals may also
act through free resources. When the first unsatisfied goal has no executable path (an
impasse), the impasse handler (a mechanism's, agents/lang/core/mechanism.py) is asked; a
goal it gives up on is failed, with the reason, and blocks the goals after it as an impasse
does (seed 000: "the agent considers a goal only when all more important goals are
satisfied"); it is looked at again every cycle and is worked on as soon as a skill path for it
is executable. A goal that comes back to a situation it was in without progress is made to
try something else, and fails after MAX_LOOPS such circles (agents/lang/execution/loops.py).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..core.conjunction import Conjunction, first_binding
from ..core.explanation import Decision, GoalPath, GoalReport, GoalStatus
from ..core.matcher import ground
from ..core.outcomes import Outcome
from ..core.program import Program
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, Var
from ..reading.goals import GoalEntry, instances, ordered, satisfied
from .bodies import body_runners, cycle_hooks
from .circles import Watcher
from .loops import MAX_LOOPS, intention
from .paths import NOTHING, Found, PathFinder, Remembered, Walk
from .state import EngineState


@dataclass(frozen=True, slots=True)
class Impasse:
    """An impasse handler's answer for one goal this cycle: a path to execute (``found``),
    a reason to give the goal up (``failed``), or neither (still working); ``note`` says
    what it did, for the goal's report."""

    found: Found | None = None
    failed: str = ""
    note: str = ""


class ImpasseHandler:
    """What the executive asks when a goal has no executable skill path (seed 000, "Problem
    Solving and Skill Learning"), and the engine around each cycle's walk. Every hook is a
    no-op here, so this class itself is the handler that leaves an impasse an impasse; a
    mechanism's handler (agents/lang/core/mechanism.py) overrides the hooks it needs."""

    def begin(self, finder: PathFinder, walk: Walk) -> None:
        """Once per cycle, before the goal walk."""

    def solve(self, finder: PathFinder, walk: Walk, entry: GoalEntry,
              unsatisfied: list) -> Impasse:
        """The answer for ``entry``, the first goal the walk reaches with no executable path
        (``unsatisfied``: its unsatisfied instances). Here: none (it stays an impasse)."""
        return Impasse()

    def agenda(self, finder: PathFinder, walk: Walk, entry: GoalEntry, conj: Conjunction,
               current: str) -> list:
        """The conjuncts of ``conj`` to pursue, best first (``current``: the one pursued last
        cycle). Here: the unsatisfied ground literal conjuncts in written order."""
        return [c for c in conj.literals if not c.negated and not c.variables()
                and not satisfied(c, walk.store)]

    def loop(self, finder: PathFinder, walk: Walk, entry: GoalEntry, reason: str) -> bool:
        """Back off after a circle (``reason``); True if it did. Here: False."""
        return False

    def possible(self, finder: PathFinder, walk: Walk, instance: Literal) -> bool:
        """False for an instance of a goal that nothing can make true (left out of the goal's
        instances). Here: True."""
        return True

    def known(self, state: EngineState, store: FactStore) -> FactStore:
        """The beliefs the walk judges goals by: ``store`` plus the handler's own facts."""
        return store

    def finish(self, decision: Decision, state: EngineState) -> tuple[Decision, EngineState]:
        """The handler's word on the cycle's decision, after the walk."""
        return decision, state


class Executive:
    """Goal-list walk for one program; pure."""

    def __init__(self, program: Program, solver: ImpasseHandler | None = None):
        self.program = program
        self.finder = PathFinder(program, body_runners(program.mechanisms))
        self.hooks = cycle_hooks(self.finder.bodies, {s.kind for s in program.skills})
        self.solver = ImpasseHandler() if solver is None else solver
        # only a handler that can rule instances out is asked about each one
        self.filters = type(self.solver).possible is not ImpasseHandler.possible

    def decide(self, state: EngineState, pidx: PerceptIndex, store: FactStore,
               outcomes: tuple[Outcome, ...] = ()) -> tuple[Decision, EngineState]:
        """(Decision, next EngineState) for one cycle."""
        walk = Walk(self.program, pidx, store, state, outcomes)
        for hook in self.hooks:
            hook.begin(self.finder, walk)
        self.solver.begin(self.finder, walk)
        reports, paths, idle, seen = [], [], [], []
        remembered = dict(state.paths)
        failed = dict(walk.current("failed"))
        goals = ordered(state.goals)
        watcher = Watcher(state.loops, pidx, store, state.cycle,
                          {e.id: e.text for e in goals}, {e.id: k for k, e in enumerate(goals)},
                          intention(state.paths, state.active,
                                    tuple(x for m in self.program.mechanisms
                                          for x in m.intention(state)), len(state.learned)))
        stop = ""  # id of the goal in impasse (or failed) that blocks the rest
        possible = self.solver.possible if self.filters else None
        ends: dict[str, str] = {}  # goal id -> why it ended this cycle (once, deadline)
        for e in goals:
            walk.goal_id = e.id
            if e.ended:  # over: reported as it ended, never pursued nor protected again
                status = GoalStatus.SATISFIED if e.ended.startswith("achieved") else \
                    GoalStatus.FAILED
                reports.append(_report(e, status, e.literal, e.ended))
                continue
            insts = instances(e.literal, self.program, pidx)
            if possible is not None and len(insts) > 1:   # never (on D D) for (on D ?x)
                insts = [i for i in insts if satisfied(i, store) or possible(self.finder, walk, i)]
            unsat = [i for i in insts if not satisfied(i, store)]
            prev = remembered.get(e.id, ())
            seen.append((e.id, not unsat))
            if not unsat and e.once:
                ends[e.id] = f"achieved at cycle {state.cycle}; once: not kept"
                reports.append(_report(e, GoalStatus.SATISFIED, e.literal, ends[e.id]))
                remembered.pop(e.id, None)
                continue
            if unsat and 0 <= e.deadline <= state.cycle:
                ends[e.id] = f"{e.text} not achieved by cycle {e.deadline}, its deadline"
                reports.append(_report(e, GoalStatus.FAILED, unsat[0], ends[e.id]))
                remembered.pop(e.id, None)
                continue
            if not unsat:
                reports.append(GoalReport(e.id, e.text, e.priority, GoalStatus.SATISFIED))
                remembered.pop(e.id, None)
                failed.pop(e.id, None)
                walk.protected.append((e.id, e.text, _held(e, insts, pidx, store)))
                continue
            waiting = GoalStatus.SUSPENDED if prev else GoalStatus.PENDING
            blocker = stop or walk.exclusive or (paths[0].goal_id if paths and
                                                 self.program.resources is None else "")
            if blocker and e.id in failed:
                reports.append(_report(e, GoalStatus.FAILED, unsat[0], failed[e.id]))
                continue
            if blocker:
                reports.append(_report(e, waiting, unsat[0], f"waits: {blocker} comes first"))
                continue
            watcher.pursued.add(e.id)
            watcher.check(e.id)
            circle = watcher.take(e.id)
            if circle:
                why = self._circle(walk, e, prev, circle, watcher)
                remembered.pop(e.id, None)
                prev = ()
                if why:
                    failed[e.id] = why
            walk.banned = watcher.banned(e.id)
            if e.id in failed:
                # given up: it blocks the goals after it, and is worked on again as soon as a
                # skill path for it is executable (seed 000: the goal list is rechecked every
                # cycle), without asking the problem solver again
                inst, found = self._first_path(walk, e, unsat, prev, False)
                if found is None:
                    reports.append(_report(e, GoalStatus.FAILED, inst, failed[e.id]))
                    stop = e.id
                    continue
                del failed[e.id]
            else:
                resume = bool(prev) and e.id not in state.active
                inst, found = self._first_path(walk, e, unsat, prev, resume)
            if found is None and paths:
                reports.append(_report(e, waiting, unsat[0], "no path with free resources"))
                continue
            if found is None:
                remembered.pop(e.id, None)   # a broken path with no alternative is forgotten
                answer = self._impasse(walk, e, unsat)
                if answer.failed:
                    circle = watcher.circle(e.id)
                    why = f"{e.text} cannot be achieved without going round in a circle " \
                          f"({circle}); {answer.failed}" if circle else answer.failed
                    failed[e.id] = why
                    reports.append(_report(e, GoalStatus.FAILED, inst, why))
                    stop = e.id   # a failed goal blocks lower ones as an impasse does
                    continue
                if answer.found is None:
                    reports.append(_report(e, GoalStatus.IMPASSE, inst,
                                           answer.note or "no executable skill path"))
                    stop = e.id   # the first unsatisfied goal blocks lower ones (seed 000)
                    continue
                found = answer.found
            steps, actions, stored = found
            if not actions and steps and steps[-1].mode == "waiting":
                # an SCS body thread waits (seed 002, section 3): lower goals go on
                remembered[e.id] = tuple(stored)
                idle.append(e.id)
                reports.append(_report(e, GoalStatus.SUSPENDED, inst,
                                       "its body thread waits (see scs)"))
                continue
            used = self.finder.take(walk, e.id, actions)
            paths.append(GoalPath(e.id, tuple(steps), tuple(actions), used, bool(paths)))
            remembered[e.id] = tuple(stored)
            note = "acts in parallel through free resources" if len(paths) > 1 else ""
            reports.append(_report(e, GoalStatus.ACTIVE, inst, note))
        for hook in self.hooks:
            hook.end(self.finder, walk, reports)
        live = {e.id for e in state.goals}
        walk.updates["failed"] = tuple(sorted((g, why) for g, why in failed.items() if g in live))
        achieved = self.finder.effects.of_actions([a for p in paths for a in p.actions])[0]
        loops = watcher.state(seen, paths[0].goal_id if paths else "",
                              tuple((x.pred, *x.args) for x in achieved), dict(remembered))
        if ends:
            walk.updates["goals"] = tuple(replace(e, ended=ends[e.id]) if e.id in ends else e
                                          for e in walk.current("goals"))
        new_state = replace(
            state, paths=tuple(sorted((k, v) for k, v in remembered.items() if k in live)),
            cycle=state.cycle + 1, active=tuple(p.goal_id for p in paths) + tuple(idle),
            loops=loops, **walk.updates)
        return Decision(state.cycle, tuple(reports), tuple(paths), tuple(walk.why),
                        tuple(walk.sections)), new_state

    def _first_path(self, walk: Walk, e: GoalEntry, unsat: list, prev: tuple,
                    resume: bool) -> tuple[Literal, Found | None]:
        """The first unsatisfied instance (for a conjunction: the first conjunct of its
        agenda) with an executable path, the one the remembered path was for first, and
        that path."""
        if isinstance(e.literal, Conjunction):   # the agenda's order is the preference
            unsat = self.solver.agenda(self.finder, walk, e, e.literal,
                                       prev[0].goal if prev else "")
            if not unsat:
                return e.literal, None
        else:
            unsat = sorted(unsat, key=lambda i: not prev or str(i) != prev[0].goal)
        for inst in unsat:
            memory = Remembered(prev, resume) if prev and prev[0].goal == str(inst) else NOTHING
            found = self.finder.achieve(walk, inst, memory, 0, frozenset())
            if found:
                return inst, found
        return unsat[0], None

    def _circle(self, walk: Walk, e: GoalEntry, prev: tuple, why: str,
                watcher: Watcher) -> str:
        """Back off after a circle (``why``): the skill the goal's last path began with is not
        used for it again in the episode, and the impasse handler backtracks; returns the
        reason to fail the goal ("" to go on): after MAX_LOOPS circles, or when there is
        nothing to back off from."""
        step = (prev[0].goal, prev[0].skill, prev[0].bindings) if prev else \
            watcher.watch(e.id).last
        if step:
            watcher.ban(e.id, step)
        if watcher.loops(e.id) > MAX_LOOPS:
            return f"{e.text} cannot be achieved without going round in a circle " \
                   f"({MAX_LOOPS + 1} returns); last: {why}"
        backed = self.solver.loop(self.finder, walk, e, why)
        return "" if step or backed else f"{e.text} cannot be achieved: {why}"

    def _impasse(self, walk: Walk, e: GoalEntry, unsat: list) -> Impasse:
        return self.solver.solve(self.finder, walk, e, unsat)


def _held(e: GoalEntry, insts: list, pidx: PerceptIndex, store: FactStore) -> tuple:
    """The ground literals by which the satisfied goal ``e`` holds (protected from lower goals'
    actions): its ground instances ``insts``, or a conjunction's conjuncts under its first
    binding."""
    if isinstance(e.literal, Conjunction):
        b = first_binding(e.literal, store, pidx) or {}
        insts = [ground(c, b) for c in e.literal.literals]
    return tuple(x for x in insts if not x.variables())


def _report(e: GoalEntry, status: GoalStatus, inst, note: str = "") -> GoalReport:
    bindings = () if not isinstance(e.literal, Literal) or not isinstance(inst, Literal) \
        or inst.pred != e.literal.pred else \
        tuple((g.name, a) for g, a in zip(e.literal.args, inst.args, strict=True)
              if isinstance(g, Var) and not isinstance(a, Var))
    return GoalReport(e.id, e.text, e.priority, status, bindings, str(inst), note)
