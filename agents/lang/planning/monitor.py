"""Monitoring execution (seed 003, section 6). The planner waits for the world's outcome of
each of a step's commands (the office world reports one when an operation ends). Until it
comes, and while the step's primary effect is not perceived, the commands still waiting are
sent again every cycle, as the world expects of a teleoreactive agent (re-sending a running
command continues it; a command lost when a realtime executive missed its deadline is
started). When they are all in, the step is judged by a second observation: its primary
effect must hold in what the robot perceives now ("ROGUE always verifies the location with a
secondary test"). A navigation reported done while the robot is elsewhere is a false
success: the state already holds the actual position (it comes from perception), and the
request is planned again from there; a step that ended without its effect (the room was
occupied) announces its :on-failure commands, is excluded for that goal while what it
brought to light stands (agents/lang/planning/memory.py), and its request is planned again:
the back-chainer backtracks to the next alternative; a failed step (a blocked door, a bump)
is retried after RETRY_AFTER cycles, by whatever route or action the state then suggests.
Effects on the planner's own predicates (no percept shows them) are taken from the outcome."""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property

from ..core.outcomes import Outcome
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal
from ..solving.state import literal
from ..solving.task import Task
from .domain import Domain, Metric, project, with_facts
from .memory import exclude
from .merge import Carry
from .state import Applied, Exclusion, Executing, PlannerState, PlanStep
from .state import Task as Request

WATCHDOG = 1200      # cycles without an outcome before a step counts as failed [cycles]
RETRY_AFTER = 10     # cycles a request waits after a failed step [cycles]
NOT_THE_WORLDS = ("stopped", "pre-empted")
"""Failure codes of an operation cancelled by the agent (or by the world's safe action for a
late agent), not failed in the world: no retry delay, no failure counted."""
MAX_HEAD = 400       # head-plan entries kept [entries]


@dataclass
class Env:
    """One cycle's view: the domain, percepts, beliefs (with the planner's facts), the
    cycle, and the travel metric (read from the percepts when first needed: at a decision
    point, not while a step runs)."""

    domain: Domain
    pidx: PerceptIndex
    store: FactStore
    cycle: int

    @cached_property
    def metric(self) -> Metric:
        return Metric(self.domain.travel, self.pidx)

    def holds(self, text: str, extra: tuple[str, ...] = ()) -> bool:
        return Task(self.domain.program, self.pidx, with_facts(self.store, extra)).holds(text)

    def place(self) -> str:
        return self.domain.place(self.store)

    def carry(self) -> Carry | None:
        """The load constraint of a merge here, when the program and percepts say it."""
        cap = self.metric.capacity
        if cap is None:
            return None
        return Carry(self.domain.carried(self.store), cap, self.domain.load_delta)


def monitor(ps: PlannerState, env: Env, outcomes: tuple[Outcome, ...],
            events: list[str]) -> PlannerState:
    """Take this cycle's outcomes for the step being executed; judge it once all are in."""
    ex = ps.executing
    if ex is None:
        return ps
    waiting, failed = list(ex.waiting), ex.failed
    for o in outcomes:
        cmd = tuple(o.action.to_list())
        if cmd in waiting:
            waiting.remove(cmd)
            if not o.ok and not failed:
                failed = o.reason or f"{o.action} failed"
    if waiting and env.cycle - ex.sent < WATCHDOG:
        ps = replace(ps, executing=replace(ex, waiting=tuple(waiting), failed=failed))
        if not env.holds(ex.step.primary):   # sent again: a running operation goes on
            ps = replace(ps, announce=ps.announce + tuple(waiting))
        return ps
    if waiting:
        failed = failed or f"no outcome for {len(waiting)} command(s) in {WATCHDOG} cycles"
    return conclude(replace(ps, executing=None), env, ex, failed, events)


def conclude(ps: PlannerState, env: Env, ex: Executing, failed: str,
             events: list[str]) -> PlannerState:
    """Record the step in the head-plan with what monitoring found, and update the tasks."""
    step, dom = ex.step, env.domain
    verified, gone = False, None
    perceived = literal(step.primary).pred not in dom.model_preds and \
        env.holds(step.primary)
    if failed and perceived:   # what is observed counts, not what was reported
        result, note, verified = "verified", f"{step.primary} observed, though the world " \
            f"reported: {failed}", True
        failed = ""
    elif failed:
        result = "interrupted" if _cancelled(failed) else "failed"
        note = failed
    elif perceived or literal(step.primary).pred in dom.model_preds:
        result, note, verified = "verified", _verified(step, env), True
    elif dom.travel is not None and literal(step.primary).pred == dom.travel.location.pred:
        result = "false-success"
        note = (f"({' '.join(map(str, step.actions[-1]))}) reported done, but the robot is "
                f"in {env.place() or 'an unknown place'} (second observation): replanning "
                f"from there")
    else:
        result = "not-achieved"
        gone = exclude(dom, step, ex.before, env.store, env.cycle)
        note = (f"{gone.why}: excluded for {gone.achieves} while "
                f"{' '.join(gone.depends) or 'that holds'}"
                f"{' holds' if gone.depends else ''}; backtracking to the next alternative")
    events.append(f"cycle {env.cycle}: {step.text} {result}: {note}")
    if step.on_failure and result == "not-achieved":
        ps = replace(ps, announce=ps.announce + step.on_failure)
        events.append(f"cycle {env.cycle}: announcing "
                      + " ".join(" ".join(map(str, a[1:])) for a in step.on_failure))
    head = (ps.head + (Applied(step.text, ex.tasks, ex.sent, env.cycle, result, note),))
    ps = replace(ps, head=head[-MAX_HEAD:])
    where = step.place if verified else env.place() if result == "false-success" else ""
    if verified:
        ps = apply_model(ps, dom, step)
    ps = replace(ps, travel=replace(ps.travel, route=_grow(ps.travel.route, where)))
    tasks = tuple(_after(t, step, where, verified, failed, env.cycle, gone)
                  if t.goal_id in ex.tasks else t for t in ps.tasks)
    return replace(ps, tasks=tasks)


def abandon(ps: PlannerState, env: Env, events: list[str]) -> PlannerState:
    """Stop waiting for a step none of whose requests is pending any more (the world did
    it, or it was withdrawn) and whose own effect has not come about: the next step's
    commands pre-empt it (seed 003, section 6: "PRODIGY is able to detect when an action
    is no longer necessary")."""
    ex, cycle = ps.executing, env.cycle
    if ex is None or any(ps.task(t) is not None for t in ex.tasks) or \
            env.holds(ex.step.primary):
        return ps
    note = "no longer needed: " + ", ".join(ex.tasks) + " done"
    events.append(f"cycle {cycle}: {ex.step.text} abandoned: {note}")
    return replace(ps, executing=None, head=(ps.head + (
        Applied(ex.step.text, ex.tasks, ex.sent, cycle, "abandoned", note),))[-MAX_HEAD:])


def apply_model(ps: PlannerState, dom: Domain, step: PlanStep) -> PlannerState:
    """The step's effects on the planner's own predicates, applied to its facts."""
    mine = tuple(e for e in step.effects if literal(e).pred in dom.model_preds)
    if not mine:
        return ps
    store = project(with_facts(FactStore(), ps.model), mine)
    facts = sorted(str(Literal(p, tuple(args))) for p, rows in store.facts.items()
                   for args in rows)
    return replace(ps, model=tuple(facts))


def _verified(step: PlanStep, env: Env) -> str:
    if not step.actions:
        return "applied in the planner's model"
    return f"{step.primary} observed" if literal(step.primary).pred not in \
        env.domain.model_preds else "done"


def _after(t: Request, step: PlanStep, where: str, verified: bool, failed: str,
           cycle: int, gone: Exclusion | None = None) -> Request:
    """A served task after its step: done (its first step leaves the tail-plan), or to be
    planned again (not achieved: the choice is excluded, ``gone``, and the plan made afresh;
    failed: retried later); ``where`` the robot went for it ("" if nowhere new)."""
    places = _grow(t.places, where)
    t = replace(t, places=places)
    if verified:
        plan = t.plan[1:] if t.plan and t.plan[0].actions == step.actions else t.plan
        return replace(t, plan=plan, places=places)
    if failed and _cancelled(failed):
        return t   # cancelled, not failed: planned again at once
    if failed:
        return replace(t, failures=t.failures + 1, retry_at=cycle + RETRY_AFTER)
    return replace(t, failures=t.failures + 1, replan=f"{step.text} did not achieve "
                   f"{step.primary}", excluded=t.excluded + ((gone,) if gone else ()))


def _cancelled(reason: str) -> bool:
    return any(f": {code}: " in reason for code in NOT_THE_WORLDS)


def _grow(route: tuple[str, ...], place: str) -> tuple[str, ...]:
    return route if not place or (route and route[-1] == place) else route + (place,)
