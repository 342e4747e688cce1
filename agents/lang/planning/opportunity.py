"""Opportunistic steps (seed 003, section 4: ROGUE identifies "when different goals could be
achieved opportunistically"; section 8: "to recognize compatible tasks and opportunistically
achieve them").

Before the robot leaves the place it is in (the merged choice's next step is somewhere
else), the first step of any selected or waiting request that is done right there (it has
commands and its place is the robot's: an acquire, a delivery, an observation) is taken
first, when doing so does not delay a more important request beyond what it would wait
anyway: the step costs no travel, and the least travel of the selected requests' remaining
steps (the merged order's, agents/lang/planning/merge.py) does not grow for it, also with
what the step adds to the load (a thing picked up must leave room for everything they still
have to carry); so the only wait it adds is its own operation, as a compatible request's
steps on the way add theirs. A request whose place is unreachable or that waits after a
failure is blocked, not waiting, and is left alone. The most important such step (priority,
then arrival) comes first; after it the choice is made again, so each step is weighed on
its own. Pure."""

from __future__ import annotations

from .merge import EPS, Carry, Choice, merger
from .monitor import Env
from .state import Task


def opportunity(tasks: list[Task], choice: Choice | None, env: Env,
                events: list[str]) -> Choice | None:
    """A step to take here before ``choice`` leaves (see the top), or None."""
    here = env.place()
    if not here or choice is None or not choice.step.place or choice.step.place == here:
        return None
    selected = [t for t in tasks if t.status == "selected" and t.plan]
    carry = env.carry()
    base = merger(env.metric, [t.plan for t in selected], carry).total()
    for t in sorted(tasks, key=lambda t: (t.priority, t.seq)):
        if t.status not in ("selected", "waiting") or not t.plan or t.goal_id in choice.tasks:
            continue
        step = t.plan[0]
        if not step.actions or step.place != here:
            continue
        after = carry
        if carry is not None:
            after = Carry(carry.now + carry.delta(step), carry.capacity, carry.delta)
            if after.now > after.capacity:
                continue
        rest = [s.plan[1:] if s.goal_id == t.goal_id else s.plan for s in selected]
        travel = merger(env.metric, [p for p in rest if p], after).total()
        if travel > base + EPS:
            continue
        events.append(f"cycle {env.cycle}: {t.goal_id} {step.text} taken in {here} before "
                      f"leaving it ({t.status}): no travel, and the selected requests' "
                      f"travel stays {base:.1f} m")
        return Choice(step, (t.goal_id,), round(base, 3), choice.order)
    return None
