"""ROGUE (seed 003) as a mechanism of the engine: ``Engine(program, solver="rogue")``, or
``[[agents]] mechanism = "rogue"`` in a scenario.

It plugs into the executive's goal walk (agents/lang/execution/executive.py) as its impasse handler.
The operators live in the program's (operators ...) section, not among its skills, so a
request (a user goal) has no skill path and reaches the planner, which answers for all
requests at once:
  ``begin`` (every cycle, before the walk): monitoring of the step being executed
  (agents/lang/planning/monitor.py), then the request handling of a decision point when no
  step is executing (agents/lang/planning/agenda.py): new requests, tail-plans, goal
  selection, the next step proposed; requests given up are failed with the reason;
  ``solve`` (for the first request the walk reaches): sends the proposed step's commands
  once (and any announcement), or nothing while a step runs (its operation goes on);
  ``known`` (Engine, before the walk): beliefs plus the facts only the planner knows, so a
  request such as (mtg-scheduled) is judged satisfied by its state model;
  ``finish`` (Engine, after the walk): each request's status as the planner sees it
  (selected: active; waiting or blocked: suspended, with why) and the "planner" section.
Everything it keeps is in EngineState.planner, so one instance serves every agent."""

from __future__ import annotations

from dataclasses import replace

from ..core.explanation import Decision, GoalReport, GoalStatus, PathStep
from ..core.program import Program
from ..core.store import FactStore
from ..core.terms import Action, Literal
from ..execution.executive import Impasse, ImpasseHandler
from ..execution.paths import PathFinder, Walk
from ..execution.state import EngineState
from ..reading.goals import GoalEntry
from .agenda import decide, sync
from .domain import Domain, refresh, with_facts
from .monitor import Env, abandon, monitor
from .section import PlannerSection
from .state import PlannerState

_STATUS = {"selected": GoalStatus.ACTIVE, "waiting": GoalStatus.SUSPENDED,
           "blocked": GoalStatus.SUSPENDED}


class RoguePlanner(ImpasseHandler):
    """Stateless between cycles (the domain of each program is cached)."""

    def __init__(self) -> None:
        self._domains: dict[int, tuple[Program, Domain]] = {}

    def domain(self, program: Program) -> Domain:
        hit = self._domains.get(id(program))
        if hit is None or hit[0] is not program:
            hit = self._domains[id(program)] = (program, Domain(program))
        return hit[1]

    # -- the engine's hooks ------------------------------------------------------------------
    def known(self, state: EngineState, store: FactStore) -> FactStore:
        """Beliefs plus the planner's own facts (its state model)."""
        return with_facts(store, state.planner.model)

    def begin(self, finder: PathFinder, walk: Walk) -> None:
        dom = self.domain(finder.program)
        ps = replace(walk.current("planner"), proposed=None, announce=())
        env = Env(dom, walk.pidx, walk.store, walk.state.cycle)
        events: list[str] = []
        failed = dict(walk.current("failed"))
        model = ps.model
        ps = monitor(ps, env, walk.outcomes, events)
        env.store = refresh(env.store, model, ps.model)
        ps = sync(ps, env, walk.state.goals, failed, events)
        ps = abandon(ps, env, events)
        section = PlannerSection(ps)
        if ps.executing is None:
            out = decide(ps, env, events)
            ps = out.state
            failed.update(out.failed)
            order = out.choice.order if out.choice else ()
            section = PlannerSection(ps, (), tuple(out.firings), order,
                                     out.choice.expected if out.choice else 0.0)
        ps = ps.with_log(events)
        walk.updates["planner"] = ps
        walk.updates["failed"] = tuple(sorted(failed.items()))
        walk.sections.append(replace(section, state=ps, events=tuple(events)))

    def solve(self, finder: PathFinder, walk: Walk, entry: GoalEntry,
              unsatisfied: list[Literal]) -> Impasse:
        ps: PlannerState = walk.current("planner")
        commands = list(ps.announce)
        ex, mode = ps.executing, "executing"
        if ps.proposed is not None:
            ex, mode = ps.proposed, "sent"
            commands += list(ex.step.actions)
            ps = replace(ps, executing=ex, proposed=None)
        walk.updates["planner"] = replace(ps, announce=())
        self._sending(walk, tuple(commands))
        if ex is None and not commands:
            why = "; ".join(f"{t.goal_id} {t.note}" for t in ps.tasks if t.note)
            return Impasse(note=f"the planner has no step to take now ({why or 'no plan'})")
        dom = self.domain(finder.program)
        steps = []
        if ex is not None:
            op = dom.operators[ex.step.clause]
            goal = next((t.goal for t in ps.tasks if t.goal_id == ex.tasks[0]), entry.text)
            steps = [PathStep(goal, ex.step.text, str(op.loc), ex.step.bindings, mode)]
        actions = [Action(str(c[0]), tuple(c[1:])) for c in commands]
        return Impasse(found=(steps, actions, []))

    def finish(self, decision: Decision, state: EngineState
               ) -> tuple[Decision, EngineState]:
        """Statuses of the requests as the planner sees them; the proposal not sent (a
        program goal acted first) is dropped."""
        ps = state.planner
        if ps.proposed is not None or ps.announce:
            ps = replace(ps, proposed=None, announce=())
            state = replace(state, planner=ps)
        reports = tuple(_report(r, ps) for r in decision.goals)
        lead = ps.executing.tasks[0] if ps.executing else ""
        paths = tuple(replace(p, goal_id=lead) if lead and p.steps and p.steps[0].skill ==
                      ps.executing.step.text else p for p in decision.paths)
        sections = tuple(replace(s, state=ps) if isinstance(s, PlannerSection) else s
                         for s in decision.sections)
        return replace(decision, goals=reports, paths=paths, sections=sections), state

    def _sending(self, walk: Walk, commands: tuple) -> None:
        for k, s in enumerate(walk.sections):
            if isinstance(s, PlannerSection):
                walk.sections[k] = replace(s, sending=commands)


def _report(r: GoalReport, ps: PlannerState) -> GoalReport:
    t = ps.task(r.id)
    if t is None or r.status in (GoalStatus.SATISFIED, GoalStatus.FAILED):
        return r
    status = _STATUS.get(t.status, r.status)
    if ps.executing is not None and r.id in ps.executing.tasks:
        status = GoalStatus.ACTIVE
    return replace(r, status=status, note=f"ROGUE: {t.note}" if t.note else r.note)

