"""SCS skill bodies in the engine: threads, their life cycle and the BodyRunner.

A body runs as a thread, one per (goal, goal instance, skill), kept in EngineState.scs. The
prioritised goal list decides which thread acts: when the executive reaches a goal whose path
enters a body skill, ``ScsBody.expand`` runs that skill's thread for one atomic step
(agents/lang/scs/constructs.py). A thread that waits (a wait point, an inactive ``:while``,
resources taken) answers with a "waiting" path and no actions: the executive then goes on to
the next goal, so other threads run (seed 002, section 3, "Multiple Threads of Execution").
A goal that is not reached keeps its thread as it is (suspended); when it is reached again
the thread resumes where it was, its condition stack checked first.

Life cycle: a thread lives while its skill stays on its goal's path. ``begin`` (every cycle,
before the goal walk) settles the outcome of each thread's last atomic step from the world's
report and drops threads whose goal is gone; ``end`` drops the threads of goals satisfied
this cycle, and those of goals that acted (or were in impasse) this cycle without running
them (the path went another way), and adds the "scs" section to the decision. A thread is
kept by nothing else, so a restarted executive given its SCS state back (docs/bus.md,
"Agent memory") resumes its threads though it remembers no skill path. A body that ended
(failed) is started afresh when its skill is entered again in a later cycle. A body that ends with
success while its goal is still false starts again at once, as a T-R program keeps running
while its goal is unachieved (seed 002, Appendix B); one that fails is passed over with the
reason, so the next skill for the goal is tried.
"""

from __future__ import annotations

from dataclasses import replace

from ..core.explanation import GoalReport, GoalStatus, PathStep
from ..core.outcomes import Outcome
from ..core.program import Skill
from ..core.terms import Literal
from ..execution.paths import Found, PathFinder, Remembered, Walk
from ..execution.state import StoredStep
from .constructs import Tick
from .results import R, Res
from .section import ScsSection
from .state import Frame, ScsState, Thread, ThreadStatus

WAITING = "waiting"
"""PathStep.mode of a body that takes no action this cycle (agents/lang/execution/executive.py)."""


def thread_key(goal_id: str, goal: str, skill: Skill) -> str:
    return f"{goal_id}|{goal}|{skill.number}"


class ScsBody:
    """The runner of ``Skill.kind == "body"`` (agents/lang/execution/bodies.py), and the per-cycle
    hooks of the SCS mechanism (``begin``/``end``)."""

    def expand(self, finder: PathFinder, walk: Walk, s: Skill, b: dict, goal: Literal,
               prev_rest: Remembered, depth: int, on_path: frozenset, step: PathStep,
               stored: StoredStep) -> Found | None:
        text = str(goal)
        key = thread_key(walk.goal_id, text, s)
        old = walk.current("scs").thread(key)
        if old is not None and old.root is None and old.last == walk.state.cycle:
            walk.passed(depth, text, s.name, b, f"its body ended this cycle: {old.note}")
            return None   # not entered again in the cycle it failed (or ended at once)
        fresh = old is None or old.root is None
        tick = Tick(finder, walk, s, key, depth, on_path, prev_rest)
        r = tick.run(s.body, None if fresh else old.root, (), dict(b))
        started = walk.state.cycle if fresh else old.started
        tally = tick.tally
        if r.kind is R.OK:
            tally["bodies succeeded"] = tally.get("bodies succeeded", 0) + 1
            if not fresh:   # ended now, goal still false: run it again (seed 002, App. B)
                tick = Tick(finder, walk, s, key, depth, on_path, prev_rest)
                tick.tally = tally
                r = tick.run(s.body, None, (), dict(b))
                started = walk.state.cycle
                if r.kind is R.OK:
                    tick.bump("bodies succeeded")
        if r.kind is R.FAIL:
            tick.bump("bodies failed")
        thread = Thread(key, walk.goal_id, text, s.number, s.name,
                        r.frame if r.kind in (R.ACT, R.IDLE) else None, _status(r),
                        _note(r, tick), started, walk.state.cycle)
        walk.updates["scs"] = walk.current("scs").with_thread(thread).counted(tick.tally)
        if r.kind is R.FAIL:
            walk.passed(depth, text, s.name, b, f"body failed: {r.why}")
            return None
        if r.kind is R.OK:
            walk.passed(depth, text, s.name, b, "body ended at once with success, but the "
                        "goal is still false")
            return None
        sub_steps, sub_actions, sub_stored = tick.sub or ([], [], [])
        if r.kind is R.IDLE:
            head = step if tick.sub else replace(step, mode=WAITING)
            return [head, *sub_steps], [], [stored, *sub_stored]
        return [step, *sub_steps], tick.actions or list(sub_actions), [stored, *sub_stored]

    # -- per-cycle hooks ---------------------------------------------------------------------
    def begin(self, finder: PathFinder, walk: Walk) -> None:
        """Drop threads whose goal is gone; settle the outcome of every thread's atomic step
        of the last cycle (also of threads whose goal is not reached this cycle)."""
        scs = walk.current("scs")
        if not scs.threads:
            return
        live = {e.id for e in walk.state.goals}
        pool = [(tuple(o.action.to_list()), o) for o in walk.outcomes]
        kept, changed = [], False
        for t in scs.threads:
            if t.goal_id not in live:
                changed = True
                continue
            root = _settle(t.root, pool, walk.state.cycle)
            changed |= root is not t.root
            kept.append(t if root is t.root else Thread(t.key, t.goal_id, t.goal, t.skill,
                                                         t.skill_name, root, t.status, t.note,
                                                         t.started, t.last))
        if changed:
            walk.updates["scs"] = replace(scs, threads=tuple(kept))

    def end(self, finder: PathFinder, walk: Walk, reports: list[GoalReport]) -> None:
        """Drop threads of goals achieved this cycle; add the "scs" section."""
        scs = walk.current("scs")
        cycle = walk.state.cycle
        done = {r.id for r in reports if r.status is GoalStatus.SATISFIED}
        worked = {r.id for r in reports if r.status in _WORKED}
        left = {t.key for t in scs.threads if t.goal_id in worked and t.last != cycle}
        if left:   # its goal went another way: the path left this skill
            scs = scs.without(left)
            walk.updates["scs"] = scs
        ended = {t.key for t in scs.threads if t.goal_id in done}
        if ended:
            n = sum(1 for t in scs.threads if t.key in ended and t.root)
            scs = scs.without(ended).counted({"bodies ended: goal achieved": n} if n else {})
            walk.updates["scs"] = scs
        if scs != ScsState() or any(s.kind == "body" for s in finder.program.skills):
            walk.sections.append(ScsSection(scs, finder.program, walk.state.cycle))


_WORKED = (GoalStatus.ACTIVE, GoalStatus.IMPASSE, GoalStatus.FAILED)
"""Goal statuses of a cycle in which its path was chosen afresh or given up: a thread of such
a goal that did not run in that cycle is no longer on its path."""


def _settle(root: Frame | None, pool: list[tuple[tuple, Outcome]], cycle: int) -> Frame | None:
    """``root`` with its atomic step of the last cycle marked done or failed by the world's
    outcomes (taken from ``pool``, each outcome used once)."""
    if root is None:
        return None
    leaf = root.leaf()
    if not leaf.pending or leaf.outcome:
        return root
    if leaf.issued != cycle - 1:
        return root.with_leaf(leaf.but(outcome="failed", reason=f"no outcome: issued at "
                                       f"cycle {leaf.issued}, now cycle {cycle}"))
    status, reason, running = "done", "", []
    for a in leaf.pending:
        j = next((k for k, (done, _) in enumerate(pool) if done == a), None)
        if j is None:  # not ended yet: an operation that lasts (the office world's *goto)
            running.append(a)
            continue
        o = pool.pop(j)[1]
        if not o.ok:
            status, reason = "failed", o.reason or "failed"
            break
    if status == "done" and running:  # sent again this cycle, which continues it
        return root.with_leaf(leaf.but(pending=tuple(running), outcome="running"))
    return root.with_leaf(leaf.but(outcome=status, reason=reason))


def _status(r: Res) -> ThreadStatus:
    if r.kind is R.OK:
        return ThreadStatus.SUCCEEDED
    if r.kind is R.FAIL:
        return ThreadStatus.FAILED
    if r.kind is R.ACT:
        return ThreadStatus.ACTING
    return r.status


def _note(r: Res, tick: Tick) -> str:
    if r.kind is R.ACT:
        if tick.actions:
            return "does " + " ".join(str(a) for a in tick.actions)
        steps = tick.sub[0] if tick.sub else ()
        return f"acts for subgoal {steps[0].goal}" if steps else "acts"
    if r.kind is R.OK:
        return "ended with success"
    return r.why
