"""PRODIGY's Back-Chainer (seed 003, Table 1) on the means-ends problem solver's chaining
code: a tail-plan for one request, built ahead of execution from the current state.

The decision points are the solver's (agents/lang/solving/search.py ``decide`` on a goal
stack, agents/lang/solving/task.py ``Task.alternatives``): pick the next unachieved literal
of the chosen way (its preconditions in written order), pick an operator that achieves it,
pick its bindings (the best-ranked first). What PRODIGY adds: the operators are chained on
even when they are applicable (``applicable=True``), the search control rules filter and
order the alternatives (agents/lang/planning/control.py), and an operator whose
preconditions hold in the *projected* state is added to the tail-plan and its effects
applied to that state, so that the next literal is judged where the plan will be, not where
the robot is. A choice that cannot be completed is given up for the next alternative and the
plan and projection are cut back to where it was made (backtracking); when the request's
goal runs out of alternatives, it cannot be achieved, with the reason. A choice excluded by
the request's failure memory (agents/lang/planning/memory.py: a step of it that did not
achieve its effect) is passed over while the exclusion stands (seed 003, section 6: "it will
backtrack to find a different action which can achieve the goal")."""

from __future__ import annotations

from dataclasses import dataclass

from ..core.matcher import subst
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, Var
from ..solving.search import decide
from ..solving.state import StackEntry, literal
from ..solving.task import Task
from .control import Control, OperatorView
from .domain import Domain, Metric, project
from .memory import excluded_here
from .state import Exclusion, PlanStep

MAX_DECISIONS = 400   # back-chaining decisions for one request [decisions]
MAX_BINDINGS = 12     # instantiations of one operator kept for a literal (Table 1, step 4)


@dataclass(frozen=True, slots=True)
class Built:
    """A tail-plan (``steps``, in execution order) or why none exists (``failed``)."""

    steps: tuple[PlanStep, ...] = ()
    failed: str = ""


class PlanTask(Task):
    """The solver's Task over the operators, in a projected state, with control rules; it
    keeps up to MAX_BINDINGS instantiations of an operator (the solver keeps fewer), so that
    backtracking can reach every room, say, after the nearest ones failed."""

    per_clause = MAX_BINDINGS

    def __init__(self, domain: Domain, pidx: PerceptIndex, store: FactStore,
                 control: Control, metric: Metric, excluded: tuple[Exclusion, ...] = (),
                 passed: dict[str, list[Exclusion]] | None = None):
        super().__init__(domain.program, pidx, store)
        self.domain = domain
        self.control = control
        self.metric = metric
        self.excluded = excluded
        self.passed = {} if passed is None else passed   # goal -> exclusions applied

    def alternatives(self, goal: Literal, applicable: bool = True,
                     concepts: bool = False):
        alts = super().alternatives(goal, applicable=True, concepts=False)
        if not alts or not self.control.rules:
            return alts
        here = self.domain.place(self.store)
        view = OperatorView(goal, [self._instance(a) for a in alts], self.store,
                            lambda p: self.metric.move(here or None, p))
        return self.control.order(view, alts)

    def admits(self, s, b: dict, goal: Literal) -> bool:
        """Not a choice the failure memory excludes for ``goal`` (those passed over are
        recorded in ``passed``)."""
        if not self.excluded:
            return True
        op = self.domain.operators[s.number]
        text = "<" + " ".join([op.name, *(str(subst(a, b)) for a in op.params)]) + ">"
        hit = excluded_here(self.excluded, str(goal), text)
        if hit is not None and hit not in self.passed.setdefault(str(goal), []):
            self.passed[str(goal)].append(hit)
        return hit is None

    def nothing_to_chain(self, goal: str) -> str:
        """Why no operator can be chained on for ``goal`` (the Back-Chainer chains on
        operators only)."""
        gone = self.passed.get(str(literal(goal)))
        if gone:
            return "every operator for it is excluded: " + "; ".join(
                f"{x.step} ({x.why})" for x in gone)
        pred = literal(goal).pred
        if not self.program.skills_for(pred):
            return f"nothing to chain off: no operator achieves {pred}"
        return (f"nothing to chain off: no operator for {pred} applies here (its :percepts "
                f"match no object)")

    def _instance(self, way) -> Literal:
        op = self.domain.operators[way.clause]
        b = dict(way.bindings)
        return Literal(op.name, tuple(b.get(a.name, a) if isinstance(a, Var) else a
                                      for a in op.params))


def build(domain: Domain, goal: Literal, store: FactStore, pidx: PerceptIndex,
          control: Control, metric: Metric, excluded: tuple[Exclusion, ...] = (),
          passed: dict[str, list[Exclusion]] | None = None) -> Built:
    """A tail-plan achieving ``goal`` from ``store`` (beliefs, the planner's facts and the
    request's knowledge), or why there is none; the choices ``excluded`` are passed over
    (those that were are added to ``passed``, goal -> exclusions)."""
    stack = [StackEntry(str(goal), "the request")]
    marks: list[tuple[int, FactStore]] = [(0, store)]
    steps: list[PlanStep] = []
    state = store
    passed = {} if passed is None else passed
    for _ in range(MAX_DECISIONS):
        task = PlanTask(domain, pidx, state, control, metric, excluded, passed)
        top = stack[-1]
        if task.holds(top.goal):
            stack.pop()
            marks.pop()
            if not stack:
                return Built(tuple(steps))
            continue
        entry, child, why = decide(task, top, [e.goal for e in stack], ready=True)
        stack[-1] = entry
        if child is not None:
            stack.append(child)
            marks.append((len(steps), state))
            continue
        if not why:   # the chosen operator is applicable in the projection: apply it
            step = domain.step(entry.decision, entry.goal, state)
            steps.append(step)
            state = project(state, step.effects)
            continue   # its goal holds now (the head is an effect): popped above
        stack.pop()
        marks.pop()
        if not stack:
            return Built(failed=f"{goal} cannot be achieved: {why}")
        n, state = marks[-1]
        del steps[n:]
        stack[-1] = stack[-1].give_up(f"its subgoal {top.goal} cannot be achieved: {why}")
    return Built(failed=f"{goal}: no tail-plan within {MAX_DECISIONS} decisions")


def check(domain: Domain, steps: tuple[PlanStep, ...], goal: Literal, store: FactStore,
          pidx: PerceptIndex) -> str:
    """"" when the tail-plan still achieves ``goal`` from ``store`` step by step (each
    step still matching its percepts, needed, and applicable in the projection), else the
    first thing that is wrong (seed 003, section 6: a step made unnecessary by the world, a
    precondition undone)."""
    state = store
    for step in steps:
        task = Task(domain.program, pidx, state)
        if task.holds(step.primary):
            return f"{step.text} is no longer needed: {step.primary} holds"
        if not domain.still_applies(step, pidx):
            return f"{step.text} no longer applies (its percepts changed)"
        missing = next((c for c in step.conditions if not task.holds(c)), None)
        if missing is not None:
            return f"{step.text}: {missing} does not hold"
        state = project(state, step.effects)
    if not Task(domain.program, pidx, state).holds(str(goal)):
        return f"the tail-plan no longer achieves {goal}"
    return ""


def first_place(steps: tuple[PlanStep, ...]) -> str:
    """Where the first step of a tail-plan is done ("" if it does not say)."""
    return steps[0].place if steps else ""


def replan_note(old: tuple[PlanStep, ...], new: tuple[PlanStep, ...]) -> str:
    """What changed between two tail-plans, for the trace."""
    gone = [s.text for s in old if s.text not in {n.text for n in new}]
    added = [s.text for s in new if s.text not in {o.text for o in old}]
    parts = ([f"skipped {' '.join(gone)}"] if gone else []) + \
        ([f"added {' '.join(added)}"] if added else [])
    return "; ".join(parts) or "same steps"

