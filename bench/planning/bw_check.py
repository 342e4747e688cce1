"""The independent check of a teleo run (bench/planning/bw_teleo.py) and its figures: the actions
the world carried out are replayed under STRIPS rules (bench/planning/bw_strips.py) from the start
state; the goal is checked on the result; every goal the run's summary calls achieved must hold
there; and the world's final state must be the replayed one (a block the physics let fall
would part them). A run that fails any of these is not solved, whatever it says. An action
the world refused changed nothing and is left out of the replay; it is counted, and so is a
refused action that STRIPS would have allowed (the world's own reasons, a block still
settling, say)."""

from __future__ import annotations

from dataclasses import dataclass, field

from bench.planning import bw_strips
from bench.planning.bw_problems import Problem
from bench.planning.bw_teleo import GOAL_CONCEPT, TeleoRun, cycle_limit

TOUCH = 0.1      # [m] a lower edge this close to a top face rests on it
ALIGNED = 0.25   # [m] centres this close in x: stacked


@dataclass(frozen=True)
class Verdict:
    """One checked run: ``solved`` (the goal holds at the end, every check passed);
    ``invalid`` (why a check failed, "" when none did); ``cycles`` (cycles until the replayed
    goal first held, the limit when it never did); ``actions`` (actions sent, all cycles);
    ``solving`` (cycles in which problem solving ran); ``idle`` (cycles before the goal held
    in which nothing was done); ``pushes`` and ``backtracks`` (the solver's chaining decisions
    and backtracks); ``refused`` (actions the world refused) and ``refused_legal`` (those
    of them STRIPS allows); ``ended``: per goal of the summary, (goal, status, note)."""

    solved: bool
    invalid: str
    cycles: int
    actions: int
    solving: int
    idle: int
    pushes: int
    backtracks: int
    wall_s: float
    ended: tuple[tuple[str, str, str], ...] = field(default_factory=tuple)
    refused: int = 0
    refused_legal: int = 0

    @property
    def unfinished(self) -> list[str]:
        """The goals that ended neither achieved nor failed with a reason."""
        return [f"{g}: {s}" for g, s, note in self.ended
                if not (s == "achieved" or (s == "failed" and note))]


def world_on(final: dict) -> frozenset[tuple[str, str]]:
    """The `on` pairs of the world's final snapshot: upright blocks resting centred on
    another block's top."""
    standing = [b for b in final.get("blocks", []) if not b.get("held_by")]
    out = set()
    for a in standing:
        for b in standing:
            if a is not b and abs(a["x"] - b["x"]) < ALIGNED and \
                    abs((a["y"] - a["height"] / 2) - (b["y"] + b["height"] / 2)) < TOUCH:
                out.add((a["name"], b["name"]))
    return frozenset(out)


def _claimed(goal: str, p: Problem) -> list[tuple[str, str]]:
    """The `on` pairs a goal of the summary stands for."""
    if goal in (f"({GOAL_CONCEPT})",) or goal.startswith("(and "):
        return p.goal("listed")
    words = goal.strip("()").split()
    if len(words) == 3 and words[0] == "on":
        return [(words[1], words[2])]
    raise ValueError(f"check: goal {goal!r} of the summary is no goal this bench posted")


def check(p: Problem, run: TeleoRun, posted: int) -> Verdict:
    """The verdict on ``run`` of problem ``p`` in which ``posted`` user goals were posted."""
    goal, limit = p.goal("listed"), cycle_limit(p.n)
    problems: list[str] = []
    state = bw_strips.initial(p.start)
    seen = state      # the state the last cycle's decision saw (before its actions)
    first, steps, idle = None, 0, 0
    if run.error:
        problems.append(run.error)
    if not bw_strips.holds(state, goal):
        first = 0
    refused = [0, 0]
    for cycle, actions in enumerate(run.actions):
        seen = state
        if first is None and not actions:
            idle += 1
        cut = len(actions) - (run.refused[cycle] if cycle < len(run.refused) else 0)
        for k, action in enumerate(actions):
            try:
                state, done = _replay(state, action, k >= cut, refused)
                steps += done
            except bw_strips.Illegal as exc:
                problems.append(f"cycle {cycle}: {exc}")
                break
        if problems:
            break
        if first is None and not bw_strips.holds(state, goal):
            first = cycle + 1
    missing = bw_strips.holds(state, goal)
    if len(run.summary_goals) != posted and not run.error:
        problems.append(f"the summary has {len(run.summary_goals)} goals of {posted} posted")
    for g in run.summary_goals:
        if g["status"] == "achieved" and bw_strips.holds(state, _claimed(g["goal"], p)):
            late = "" if bw_strips.holds(seen, _claimed(g["goal"], p)) else \
                " (it held when the last cycle's decision was taken; that cycle's action undid it)"
            problems.append(f"the summary says {g['goal']} achieved; it is false at the "
                            f"end{late}")
    placed = {(f[1], f[2]) for f in state if f[0] == "on"}
    if run.final and not problems and world_on(run.final) != placed:
        problems.append(f"the world's final state differs from the replayed one: world "
                        f"{sorted(world_on(run.final) - placed)} not replayed, replayed "
                        f"{sorted(placed - world_on(run.final))} not in the world")
    invalid = "; ".join(problems)
    return Verdict(not missing and not invalid, invalid,
                   first if first is not None and not invalid else limit, steps,
                   sum(run.solving), idle, run.pushes, run.backtracks, run.wall_s,
                   tuple((g["goal"], g["status"], g.get("note", "")) for g in run.summary_goals),
                   *refused)


def _replay(state: bw_strips.State, action: list, was_refused: bool,
            refused: list[int]) -> tuple[bw_strips.State, int]:
    """(the state after ``action``, 1 if it was done); a refused action changes nothing and
    is counted in ``refused`` (the count, and the count of those STRIPS allows)."""
    step = bw_strips.from_teleo(action)
    if step is None:
        return state, 0
    if not was_refused:
        return bw_strips.apply(state, step), 1
    refused[0] += 1
    try:
        bw_strips.apply(state, step)
        refused[1] += 1
    except bw_strips.Illegal:
        pass
    return state, 0
