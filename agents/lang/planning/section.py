"""The planner's part of a Decision (explanation.Section, name "planner"): the head-plan,
the step being executed, each request's tail-plan with its status, the merged order with its
expected travel, the control rules that fired and what monitoring found this cycle, the
choices excluded by failed steps (failure memory: which, why, while what holds), and the
travel figures (seed 003: "the head-plan, tail-plan, merged order, rule firings and
monitoring results are part of the intention")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .state import PlannerState

HEAD_SHOWN = 12   # head-plan entries shown in the explanation [entries]


@dataclass(frozen=True, slots=True)
class PlannerSection:
    """``state``: the planner's state after this cycle; ``events``: what it did this cycle
    (requests added, tail-plans made or replanned, steps sent, monitoring results);
    ``firings``: control rules that fired; ``order``: the merged order of the selected
    requests' visits ("task place" each) and ``expected`` its travel [m] from here;
    ``sending``: the commands sent this cycle."""

    state: PlannerState
    events: tuple[str, ...] = ()
    firings: tuple[str, ...] = ()
    order: tuple[str, ...] = ()
    expected: float = 0.0
    sending: tuple[tuple, ...] = ()
    name: str = "planner"

    def to_dict(self) -> dict[str, Any]:
        ps = self.state
        ex = ps.executing
        return {
            "head": [a.to_dict() for a in ps.head],
            "executing": None if ex is None else {
                "step": ex.step.text, "tasks": list(ex.tasks), "sent": ex.sent,
                "waiting": [list(a) for a in ex.waiting]},
            "tails": [{"id": t.goal_id, "goal": t.goal, "priority": t.priority,
                       "status": t.status, "note": t.note,
                       "plan": [s.text for s in t.plan],
                       "excluded": [x.describe() for x in t.excluded]} for t in ps.tasks],
            "order": {"visits": list(self.order), "expected_m": self.expected},
            "firings": list(self.firings), "events": list(self.events),
            "sending": [list(a) for a in self.sending],
            "finished": [{"id": f.goal_id, "goal": f.goal, "status": f.status,
                          "reason": f.reason,
                          "excluded": [x.describe() for x in f.excluded]}
                         for f in ps.finished],
            "model": list(ps.model),
            "travel": ps.travel.to_dict()}

    def lines(self) -> list[str]:
        ps = self.state
        out = [f"planner (ROGUE, seed 003): head-plan {len(ps.head)} step(s)"]
        for a in ps.head[-HEAD_SHOWN:]:
            out.append(f"  {a.ended:>5} {a.step} for {' '.join(a.tasks)}: {a.result}"
                       + (f" ({a.note})" if a.note else ""))
        if ps.executing is not None:
            ex = ps.executing
            out.append(f"  executing {ex.step.text} for {' '.join(ex.tasks)} (sent at cycle "
                       f"{ex.sent}), waiting for "
                       + (" ".join("(" + " ".join(map(str, a)) + ")" for a in ex.waiting)
                          or "nothing"))
        out.append("tail-plans:" if ps.tasks else "tail-plans: none (no pending request)")
        for t in ps.tasks:
            out.append(f"  {t.goal_id} p{t.priority} {t.status} {t.goal}"
                       + (f" -- {t.note}" if t.note else ""))
            out.append("    " + (" ".join(s.text for s in t.plan) or "(to be planned)"))
            out += [f"    excluded: {x.describe()}" for x in t.excluded]
        if self.order:
            out.append(f"merged order ({self.expected:.1f} m from here): "
                       + " ".join(self.order))
        out += [f"rule fired: {f}" for f in self.firings]
        if self.sending:
            out.append("sending: " + " ".join("(" + " ".join(map(str, a)) + ")"
                                              for a in self.sending))
        if self.events:
            out.append("planner events:")
            out += [f"  {e}" for e in self.events]
        tr = ps.travel
        if tr.start:
            out.append(f"travel by the map: {tr.executed_m:.1f} m executed from {tr.start}; "
                       f"first-come-first-served {tr.fcfs_m:.1f} m")
        return out
