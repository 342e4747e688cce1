"""Merging head-plans (seed 003, section 4, Figures 4-6): "among the applicable actions of
all tail-plans, ROGUE selects the one that minimizes the expected total traveled distance
from the current location". Each selected request's tail-plan is a sequence of visits (the
places of its steps, consecutive steps at one place being one visit); the expected total
travel of a first step is the distance to its place plus the shortest way to do every
remaining visit of every plan, each plan in its own order (an exact search over the
interleavings, memoised, when there are at most MAX_STATES of them, otherwise nearest
first). Steps at the place the robot is in cost nothing, so an action another plan also
needs is done once. Ties (equal distance) go first to a step of the request(s) the last
action served, then to the most recent request. Pure."""

from __future__ import annotations

from dataclasses import dataclass
from math import prod

from .domain import Metric
from .state import PlanStep

MAX_STATES = 20_000   # interleavings searched exactly [states]
EPS = 1e-6            # [m] distances closer than this are equal


@dataclass(frozen=True, slots=True)
class Choice:
    """The next step: its task (the first of ``tasks``, in arrival order, names it), every
    task whose first step is the same action, the expected total travel [m] and the whole
    merged order it leads to ("task place", one per visit)."""

    step: PlanStep
    tasks: tuple[str, ...]
    expected: float
    order: tuple[str, ...]


def visits(steps: tuple[PlanStep, ...]) -> tuple[str, ...]:
    """The places of a tail-plan's steps, consecutive repeats (and unknown places) merged."""
    out: list[str] = []
    for s in steps:
        if s.place and (not out or out[-1] != s.place):
            out.append(s.place)
    return tuple(out)


class Planner:
    """The shortest completion of several visit sequences from the robot's position."""

    def __init__(self, metric: Metric, plans: list[tuple[str, ...]]):
        self.metric = metric
        self.plans = plans
        self.memo: dict[tuple, tuple[float, int]] = {}
        self.exact = prod(len(p) + 1 for p in plans) <= MAX_STATES

    def rest(self, idx: tuple[int, ...], cur: str | None) -> float:
        """The least travel to finish every plan from visit indexes ``idx`` at ``cur``."""
        return self._best(idx, cur)[0]

    def _best(self, idx: tuple[int, ...], cur: str | None) -> tuple[float, int]:
        key = (idx, cur)
        hit = self.memo.get(key)
        if hit is not None:
            return hit
        best = (0.0, -1)
        options = [(self.metric.move(cur, p[i]), k) for k, (p, i) in
                   enumerate(zip(self.plans, idx, strict=True)) if i < len(p)]
        if options and not self.exact:    # nearest first
            leg, k = min(options)
            nxt = idx[:k] + (idx[k] + 1,) + idx[k + 1:]
            best = (leg + self._best(nxt, self.plans[k][idx[k]])[0], k)
        elif options:
            best = (float("inf"), -1)
            for leg, k in options:
                nxt = idx[:k] + (idx[k] + 1,) + idx[k + 1:]
                total = leg + self._best(nxt, self.plans[k][idx[k]])[0]
                if total < best[0] - EPS:
                    best = (total, k)
        self.memo[key] = best
        return best

    def total(self) -> float:
        return self.rest(tuple(0 for _ in self.plans), None)

    def sequence(self) -> list[int]:
        """The plans' indexes in the order of the optimal visits."""
        idx, cur, out = tuple(0 for _ in self.plans), None, []
        while True:
            _, k = self._best(idx, cur)
            if k < 0:
                return out
            out.append(k)
            cur = self.plans[k][idx[k]]
            idx = idx[:k] + (idx[k] + 1,) + idx[k + 1:]


def choose(metric: Metric, plans: dict[str, tuple[PlanStep, ...]], seq: dict[str, int],
           last: tuple[str, ...]) -> Choice | None:
    """The next step among the first steps of ``plans`` (task id -> tail-plan, non-empty);
    ``seq``: arrival order of each task; ``last``: the tasks the last action served."""
    ids = [t for t in sorted(plans, key=lambda t: seq[t]) if plans[t]]
    if not ids:
        return None
    vis = [visits(plans[t]) for t in ids]
    search = Planner(metric, vis)
    scored = []
    for k, t in enumerate(ids):
        if not vis[k]:
            scored.append((0.0, t))
            continue
        idx = tuple(1 if j == k else 0 for j in range(len(ids)))
        cost = metric.move(None, vis[k][0]) + search.rest(idx, vis[k][0])
        scored.append((cost, t))
    low = min(c for c, _ in scored)
    tied = [t for c, t in scored if c <= low + EPS]
    pick = min(tied, key=lambda t: (t not in last, -seq[t]))
    step = plans[pick][0]
    same = tuple(t for t in ids if plans[t][0].actions == step.actions and
                 (step.actions or t == pick))
    name = same[0]
    order: list[str] = []
    done = [0] * len(ids)
    for k in search.sequence() if search.exact else ():
        order.append(f"{ids[k]} {vis[k][done[k]]}")
        done[k] += 1
    return Choice(plans[name][0], same, round(low, 3), tuple(order))


def detour(metric: Metric, top: list[tuple[str, ...]], other: tuple[str, ...]) -> float:
    """How much doing ``other``'s visits along with the ``top`` plans adds to their least
    travel [m] (seed 003, Table 2: compatible-with-top-priority-goal)."""
    return Planner(metric, [*top, other]).total() - Planner(metric, top).total()


def fcfs(metric: Metric, start: str, places: list[tuple[str, ...]]) -> float:
    """The travel [m] of doing each request's places in turn, in arrival order, from
    ``start``: a first-come-first-served robot (seed 003, section 4)."""
    route = [p for ps in places for p in ps]
    return metric.length(start, route)
