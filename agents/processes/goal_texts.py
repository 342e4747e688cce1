"""How the goal-entry process words what it refuses or warns about: a scripted request
refused (for the run's summary) and a priority that would outrank the program's standing
goals (docs/scenarios.md, "Priorities")."""

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
