"""ROGUE's request handling at each decision point (seed 003, sections 4 and 6):

1. ``sync``: a request posted since (a user goal the planner has no task for) is added to
   the pending goals, with the knowledge its request rule adds to the state model; a goal
   withdrawn is dropped; a request whose goal holds is done (also when the world did it).
2. ``decide``: every pending request's tail-plan is checked against the current state (the
   tail-plans of suspended requests are kept while they still hold) and planned again by the
   back-chainer when it does not; the goal control rules select the requests to work on
   (Table 2: the top priority and those compatible with it; the others wait); requests whose
   next place is unreachable, or that wait after a failure, are blocked; planner-only steps
   (no command) are applied in the model at once; among the first steps of the selected
   tail-plans the one of least expected travel is proposed (agents/lang/planning/merge.py),
   unless it leaves the place the robot is in while a step of a selected or waiting request
   can be done there at no cost to the others (agents/lang/planning/opportunity.py).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from ..core.conjunction import Conjunction
from ..reading.goals import GoalEntry, ordered
from ..solving.state import literal
from .backchain import build, check, replan_note
from .control import Control, GoalView
from .domain import with_facts
from .memory import objects, perceived_about, reopen
from .merge import Choice, choose, detour, fcfs, visits
from .monitor import Env, apply_model
from .opportunity import opportunity
from .state import Applied, Executing, Finished, PlannerState, Task

MAX_MERGED = 4          # lower-priority requests merged with the top-priority ones [requests]
MAX_FAILURES = 5        # failed or unachieved steps before a request is given up [steps]
BLOCKED_LIMIT = 600     # cycles a request may stay blocked before it is given up [cycles]


@dataclass
class Decided:
    """What ``decide`` found: the state, the requests given up (id -> reason), the merged
    order and its expected travel, the rule firings."""

    state: PlannerState
    failed: dict[str, str] = field(default_factory=dict)
    choice: Choice | None = None
    firings: list[str] = field(default_factory=list)


def sync(ps: PlannerState, env: Env, goals: tuple[GoalEntry, ...], failed: dict[str, str],
         events: list[str]) -> PlannerState:
    """Bring the tasks in line with the user goals (step 1 above)."""
    user = {e.id: e for e in goals if e.origin == "user"}
    tasks, done = [], list(ps.finished)
    for t in ps.tasks:
        e = user.get(t.goal_id)
        if e is None:
            done.append(_finish(t, env.cycle, "cancelled", "withdrawn by the user"))
            events.append(f"cycle {env.cycle}: {t.goal_id} withdrawn: its tail-plan is dropped")
        elif env.holds(t.goal, t.knowledge):
            done.append(_finish(t, env.cycle, "achieved"))
            running = ps.executing.step.text if ps.executing else ""
            rest = " ".join(s.text for s in t.plan if s.text != running)
            events.append(f"cycle {env.cycle}: {t.goal_id} {t.goal} achieved" + (
                f"; steps made unnecessary by the world, skipped: {rest}" if rest else ""))
        else:
            tasks.append(replace(t, priority=e.priority))
    known = {t.goal_id for t in ps.tasks} | {f.goal_id for f in ps.finished}
    start = ps.travel.start
    for e in ordered(tuple(user.values())):
        if e.id in known or e.id in failed:
            continue
        start = start or env.place()
        t = Task(e.id, e.text, e.priority, e.seq, env.cycle,
                 env.domain.knowledge(e.literal, env.pidx, env.store))
        if isinstance(e.literal, Conjunction):
            failed[e.id] = (f"{e.text}: the planner takes a request for one literal; post "
                            "each conjunct as a request of its own")
            done.append(_finish(t, env.cycle, "failed", failed[e.id]))
        elif e.literal.variables():
            failed[e.id] = f"{e.text}: the planner takes requests without variables"
            done.append(_finish(t, env.cycle, "failed", failed[e.id]))
        elif env.holds(t.goal, t.knowledge):
            done.append(_finish(t, env.cycle, "achieved", "held when it arrived"))
        else:
            tasks.append(t)
        events.append(f"cycle {env.cycle}: request {e.id} {e.text} (priority {e.priority}) "
                      "added to the pending goals")
    travel = replace(ps.travel, start=start)
    return replace(ps, tasks=tuple(sorted(tasks, key=lambda t: t.seq)), finished=tuple(done),
                   travel=travel)


def decide(ps: PlannerState, env: Env, events: list[str]) -> Decided:
    """Plan, select and propose the next step (step 2 above)."""
    out = Decided(ps)
    control = Control(env.domain.rules, out.firings)
    before = {t.goal_id: (t.status, t.note) for t in ps.tasks}
    tasks = [reopen(t, lambda f, t=t: env.holds(f, t.knowledge), env.cycle, events)
             for t in ps.tasks]
    tasks = [t for t in (_planned(t, env, control, out, events) for t in tasks) if t]
    for _ in range(8):   # planner-only steps are applied at once, then the choice is redone
        ready = [_gate(t, env, out, events) for t in tasks]
        tasks = [t for t in ready if t.goal_id not in out.failed]
        selected = _select(tasks, env, control)
        tasks = [selected.get(t.goal_id, t) for t in tasks]
        plans = {t.goal_id: t.plan for t in tasks if t.status == "selected" and t.plan}
        last = ps.head[-1].tasks if ps.head else ()
        out.choice = choose(env.metric, plans, {t.goal_id: t.seq for t in tasks}, last,
                            env.carry())
        step = out.choice.step if out.choice else None
        if step is None or step.actions:
            break
        ps = apply_model(ps, env.domain, step)
        ps = replace(ps, head=ps.head + (Applied(step.text, out.choice.tasks, env.cycle,
                                                 env.cycle, "applied",
                                                 "no command: the planner's model only"),))
        events.append(f"cycle {env.cycle}: {step.text} applied in the planner's model")
        tasks = [replace(t, plan=t.plan[1:]) if t.goal_id in out.choice.tasks else t
                 for t in tasks]
    for t in tasks:
        if before.get(t.goal_id, ("new", ""))[0] != t.status and t.status != "new":
            events.append(f"cycle {env.cycle}: {t.goal_id} {t.status}: {t.note}")
    out.choice = opportunity(tasks, out.choice, env, events) or out.choice
    proposed = None
    if out.choice is not None and out.choice.step.actions:
        step = out.choice.step
        proposed = Executing(step, out.choice.tasks, env.cycle, step.actions,
                             before=perceived_about(env.domain, env.store, objects(step)))
    done = ps.finished + tuple(_finish(t, env.cycle, "failed", out.failed[t.goal_id])
                               for t in ps.tasks if t.goal_id in out.failed)
    ps = replace(ps, tasks=tuple(t for t in tasks if t.goal_id not in out.failed),
                 finished=done, proposed=proposed)
    out.state = replace(ps, travel=figures(ps, env))
    return out


def _planned(t: Task, env: Env, control: Control, out: Decided, events: list[str]
             ) -> Task | None:
    """``t`` with a tail-plan that holds in the current state (kept, or made afresh)."""
    goal = literal(t.goal)
    base = with_facts(env.store, t.knowledge)
    fired = len(control.firings)
    why = t.replan or (check(env.domain, t.plan, goal, base, env.pidx) if t.plan else "")
    if t.plan and not why:
        return t
    passed: dict = {}
    built = build(env.domain, goal, base, env.pidx, control, env.metric, t.standing(), passed)
    if built.failed:
        out.failed[t.goal_id] = built.failed
        events.append(f"cycle {env.cycle}: {t.goal_id} failed: {built.failed}")
        return None
    shown = " ".join(s.text for s in built.steps)
    events.append(f"cycle {env.cycle}: {t.goal_id} " + (
        f"replanned ({why}): {replan_note(t.plan, built.steps)}" if why else
        f"tail-plan: {shown}"))
    events += [f"cycle {env.cycle}: rule fired: {f}" for f in control.firings[fired:]]
    events += [f"cycle {env.cycle}: {t.goal_id} passes over {x.step} for {x.achieves}: "
               f"excluded since cycle {x.since}" for xs in passed.values() for x in xs]
    return replace(t, plan=built.steps, replan="")


def _gate(t: Task, env: Env, out: Decided, events: list[str]) -> Task:
    """Blocked (a place of its tail-plan unreachable: it is not started, or not carried on,
    until a route is known; or waiting after a failure), or given up."""
    if t.failures >= MAX_FAILURES:
        out.failed[t.goal_id] = f"{t.goal}: given up after {t.failures} failed steps"
        events.append(f"cycle {env.cycle}: {t.goal_id} failed: {out.failed[t.goal_id]}")
        return t
    place = next((s.place for s in t.plan if not env.metric.reachable(s.place)), "")
    if place:
        since = t.blocked_since if t.blocked_since >= 0 else env.cycle
        if env.cycle - since > BLOCKED_LIMIT:
            out.failed[t.goal_id] = f"{t.goal}: {place} unreachable since cycle {since}"
        return replace(t, status="blocked", blocked_since=since,
                       note=f"{place} is unreachable (since cycle {since})")
    if t.retry_at > env.cycle:
        return replace(t, status="blocked", blocked_since=-1,
                       note=f"retries at cycle {t.retry_at} after a failed step")
    return replace(t, blocked_since=-1, status="new" if t.status == "blocked" else t.status)


def _select(tasks: list[Task], env: Env, control: Control) -> dict[str, Task]:
    """The goal decision (seed 003, Table 2): statuses selected / waiting."""
    pool = [t for t in tasks if t.status != "blocked" and t.plan]
    if not pool:
        return {}
    low = min(t.priority for t in pool)
    top = [visits(t.plan) for t in pool if t.priority == low]
    extra = {t.goal_id: detour(env.metric, top, visits(t.plan)) for t in pool
             if t.priority != low}
    travel = env.domain.travel
    limit = travel.detour if travel else 0.0
    by_id = {t.goal_id: t for t in pool}
    view = GoalView([t.goal_id for t in pool], lambda g: by_id[g].priority == low,
                    lambda g: g in extra and extra[g] <= limit,
                    lambda g: f"{g} {by_id[g].goal}")
    chosen = control.select_goals(view) if control.selects_goals else list(by_id)
    merged = sorted((g for g in chosen if g in extra), key=lambda g: (extra[g], by_id[g].seq))
    keep = {g for g in chosen if g not in extra} | set(merged[:MAX_MERGED])
    tops = ", ".join(t.goal_id for t in pool if t.priority == low)
    out = {}
    for g, t in by_id.items():
        if g in keep:
            note = "top priority" if g not in extra else \
                f"compatible with {tops}: adds {extra[g]:.1f} m"
            out[g] = replace(t, status="selected", note=note)
        else:
            why = f"adds {extra[g]:.1f} m to {tops}" if g in extra else "not selected"
            out[g] = replace(t, status="waiting", note=f"waits: {why}; its tail-plan is kept")
    return out


def figures(ps: PlannerState, env: Env) -> object:
    """The travel figures by the map: the executed route and first-come-first-served."""
    jobs = sorted([*ps.finished, *ps.tasks], key=lambda j: j.seq)
    return replace(ps.travel,
                   executed_m=env.metric.length(ps.travel.start, list(ps.travel.route)),
                   fcfs_m=fcfs(env.metric, ps.travel.start, [j.places for j in jobs]))


def _finish(t: Task, cycle: int, status: str, reason: str = "") -> Finished:
    return Finished(t.goal_id, t.goal, t.priority, t.seq, t.arrived, cycle, status, reason,
                    t.places, t.excluded)
