"""How the goal-entry process words what it refuses or warns about: a scripted request
refused (for the run's summary), a priority that would outrank the program's standing
goals (docs/scenarios.md, "Priorities") and a program goal that a request would change."""

from __future__ import annotations

from agents.lang.core.limits import shorten


def refused_text(op: str, goal_id: str, goal: str, cycle: int, reason: object) -> str:
    """How a run's summary tells a scripted request that was refused: `scripted cancel of
    g1 at cycle 300 refused: ...` (said in the summary, not only in a log)."""
    what = f"{op} of {goal_id}" if goal_id else f"{op} of {shorten(goal)}"
    return f"scripted {what} at cycle {cycle} refused: {reason}"


def rank_problem(standing: tuple[str, ...], priority: int) -> str:
    """Why a user goal of ``priority`` would rank above some of the program's standing goals
    (``standing``: their texts in file order; they have priorities 1..n, ids p1..pn), or ""
    when it ranks after all of them. A goal ranks after every goal of priority <= its own
    (docs/scenarios.md, "Priorities"), so any priority below n puts it before p(P+1)..pn,
    which in the driving program are laws: the car would break them for the errand."""
    above = [(k + 1, goal) for k, goal in enumerate(standing) if k + 1 > priority]
    if not above:
        return ""
    shown = ", ".join(f"p{k} {goal}" for k, goal in above[:3])
    more = f" and {len(above) - 3} more" if len(above) > 3 else ""
    return (f"priority {priority} ranks the goal above the program's standing goal"
            f"{'s' if len(above) > 1 else ''} {shown}{more}: the agent would pursue it before "
            f"them, at their expense; give priority {len(standing)} or more, or force it")


def program_goal_problem(standing: tuple[str, ...], agent: str, goal_id: str, op: str) -> str:
    """Why `op` (cancel, priority) may not change `goal_id` of `agent`, or "" for a user
    goal: a program goal (p1..pn: the program's own, in its order; user goals are g1, g2,
    ...) cannot be cancelled nor reprioritised, and a p-id the program lacks is named."""
    number = goal_id[1:]
    if goal_id[:1] != "p" or not number.isdigit() or number.startswith("0"):
        return ""
    ids = {0: "none", 1: "p1"}.get(len(standing), f"p1..p{len(standing)}")
    if int(number) > len(standing):
        return f"no goal {goal_id!r}: the program goals of {agent} are {ids}"
    what = "cancelled" if op == "cancel" else "given another priority"
    return (f"{goal_id} is a program goal of {agent}, {standing[int(number) - 1]}: it cannot "
            f"be {what} (program goals rank in the program's order; user goals are g1, g2, "
            "...)")
