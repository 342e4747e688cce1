"""The executive (seed 000, "Inference and Execution Mechanisms", "Adding Goal Priorities").

Each cycle it walks the prioritized goal list; the first unsatisfied goal gets a skill path
(agents/lang/paths.py: how a path is chosen). Achieved goals are rechecked every cycle and a
violated higher goal suspends the current one, which later resumes its remembered path if
every skill on it could be started now, and chooses afresh otherwise. With a (resources ...)
section, lower goals may also act through free resources. When the first unsatisfied goal
has no executable path (an impasse), the impasse handler (the means-ends problem solver,
agents/lang/solving) is asked; a goal it gives up on is failed, with the reason, and no
longer blocks the goals after it, until a skill path for it is executable again.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Protocol

from .bodies import body_runners, cycle_hooks
from .explanation import Decision, GoalPath, GoalReport, GoalStatus
from .goals import GoalEntry, instances, ordered, satisfied
from .outcomes import Outcome
from .paths import NOTHING, Found, PathFinder, Remembered, Walk
from .program import Program
from .state import EngineState
from .store import FactStore, PerceptIndex
from .terms import Literal, Var


@dataclass(frozen=True, slots=True)
class Impasse:
    """An impasse handler's answer for one goal this cycle: a path to execute (``found``),
    a reason to give the goal up (``failed``), or neither (still working); ``note`` says
    what it did, for the goal's report."""

    found: Found | None = None
    failed: str = ""
    note: str = ""


class ImpasseHandler(Protocol):
    """What the executive asks when a goal has no executable skill path (seed 000, "Problem
    Solving and Skill Learning"). ``begin`` runs once per cycle before the goal walk."""

    def begin(self, finder: PathFinder, walk: Walk) -> None: ...

    def solve(self, finder: PathFinder, walk: Walk, entry: GoalEntry,
              unsatisfied: list[Literal]) -> Impasse: ...


class Executive:
    """Goal-list walk for one program; pure."""

    def __init__(self, program: Program, solver: ImpasseHandler | None = None):
        self.program = program
        self.finder = PathFinder(program, body_runners())
        self.hooks = cycle_hooks(self.finder.bodies, {s.kind for s in program.skills})
        self.solver = solver

    def decide(self, state: EngineState, pidx: PerceptIndex, store: FactStore,
               outcomes: tuple[Outcome, ...] = ()) -> tuple[Decision, EngineState]:
        """(Decision, next EngineState) for one cycle."""
        walk = Walk(self.program, pidx, store, state, outcomes)
        for hook in self.hooks:
            hook.begin(self.finder, walk)
        if self.solver is not None:
            self.solver.begin(self.finder, walk)
        reports, paths, idle = [], [], []
        remembered = dict(state.paths)
        failed = dict(walk.current("failed"))
        stop = ""  # id of the goal in impasse that blocks the rest
        for e in ordered(state.goals):
            walk.goal_id = e.id
            unsat = [i for i in instances(e.literal, self.program, pidx) if not satisfied(i, store)]
            prev = remembered.get(e.id, ())
            if not unsat:
                reports.append(GoalReport(e.id, e.text, e.priority, GoalStatus.SATISFIED))
                remembered.pop(e.id, None)
                failed.pop(e.id, None)
                continue
            waiting = GoalStatus.SUSPENDED if prev else GoalStatus.PENDING
            blocker = stop or walk.exclusive or (paths[0].goal_id if paths and
                                                 self.program.resources is None else "")
            if e.id in failed:
                # given up, so it blocks no one; but a goal is worked on again as soon as a
                # skill path for it is executable (seed 000: the goal list is rechecked
                # every cycle), without asking the problem solver again
                inst, found = (unsat[0], None) if blocker else \
                    self._first_path(walk, unsat, prev, False)
                if found is None:
                    reports.append(_report(e, GoalStatus.FAILED, unsat[0], failed[e.id]))
                    continue
                del failed[e.id]
            elif blocker:
                reports.append(_report(e, waiting, unsat[0], f"waits: {blocker} comes first"))
                continue
            else:
                resume = bool(prev) and e.id not in state.active
                inst, found = self._first_path(walk, unsat, prev, resume)
            if found is None and paths:
                reports.append(_report(e, waiting, unsat[0], "no path with free resources"))
                continue
            if found is None:
                remembered.pop(e.id, None)   # a broken path with no alternative is forgotten
                inst, answer = unsat[0], self._impasse(walk, e, unsat)
                if answer.failed:
                    failed[e.id] = answer.failed
                    reports.append(_report(e, GoalStatus.FAILED, inst, answer.failed))
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
        new_state = replace(
            state, paths=tuple(sorted((k, v) for k, v in remembered.items() if k in live)),
            cycle=state.cycle + 1, active=tuple(p.goal_id for p in paths) + tuple(idle),
            **walk.updates)
        return Decision(state.cycle, tuple(reports), tuple(paths), tuple(walk.why),
                        tuple(walk.sections)), new_state

    def _first_path(self, walk: Walk, unsat: list[Literal], prev: tuple,
                    resume: bool) -> tuple[Literal, Found | None]:
        """The first unsatisfied instance with an executable path (the one the remembered
        path was for first), and that path."""
        unsat = sorted(unsat, key=lambda i: not prev or str(i) != prev[0].goal)
        for inst in unsat:
            memory = Remembered(prev, resume) if prev and prev[0].goal == str(inst) else NOTHING
            found = self.finder.achieve(walk, inst, memory, 0, frozenset())
            if found:
                return inst, found
        return unsat[0], None

    def _impasse(self, walk: Walk, e: GoalEntry, unsat: list[Literal]) -> Impasse:
        if self.solver is None:
            return Impasse()
        return self.solver.solve(self.finder, walk, e, unsat)


def _report(e: GoalEntry, status: GoalStatus, inst: Literal, note: str = "") -> GoalReport:
    bindings = tuple((g.name, a) for g, a in zip(e.literal.args, inst.args, strict=True)
                     if isinstance(g, Var) and not isinstance(a, Var))
    return GoalReport(e.id, e.text, e.priority, status, bindings, str(inst), note)
