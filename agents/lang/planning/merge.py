"""Merging head-plans (seed 003, section 4, Figures 4-6): "among the applicable actions of
all tail-plans, ROGUE selects the one that minimizes the expected total traveled distance
from the current location". Each selected request's tail-plan is a sequence of visits (the
places of its steps, consecutive steps at one place being one visit); the expected total
travel of a first step is the distance to its place plus the shortest way to do every
remaining visit of every plan, each plan in its own order: an exact search over the
interleavings, memoised, when there are at most MAX_STATES of them; beyond, a beam search
over the same interleavings that keeps the MAX_BEAM shortest partial orders at each depth
(within a few per cent of the exact one where both can be run). Steps at the place the robot
is in cost nothing, so an action another plan also needs is done once. Where the program
says what the robot carries and how much it can (``(travel ... :carrying ... :capacity
...)``), a visit that would carry more than the capacity is not an option at that point of
an order. Ties (equal distance) go first to a step where the robot is (done now, it cannot
be missed later), then to a step of the request(s) the last action served, then to the most
recent request. A step that several plans begin with (one goto) is done for those whose
visit the order makes there now. Pure."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from math import prod

from .domain import Metric
from .state import PlanStep

MAX_STATES = 20_000   # interleavings searched exactly [states]
MAX_BEAM = 200        # partial orders kept per depth beyond that [orders]
EPS = 1e-6            # [m] distances closer than this are equal
INF = float("inf")


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


def visit_loads(steps: tuple[PlanStep, ...], delta) -> tuple[int, ...]:
    """What each visit of ``visits(steps)`` changes in the load the robot carries (the sum
    of ``delta(step)`` over its steps; a step of unknown place counts with the visit
    before it)."""
    out: list[int] = []
    last = ""
    for s in steps:
        if s.place and s.place != last:
            out.append(0)
            last = s.place
        if out:
            out[-1] += delta(s)
    return tuple(out)


@dataclass(frozen=True, slots=True)
class Carry:
    """What the robot carries (``now``), how much it can (``capacity``), and ``delta``, what a
    step changes in it (+1 takes a thing, -1 leaves one)."""

    now: int
    capacity: int
    delta: Callable[[PlanStep], int]


@dataclass(frozen=True, slots=True)
class Load:
    """The load constraint of a merge: ``now`` what the robot carries, ``capacity`` how much
    it can, ``deltas`` per plan the change each visit makes."""

    now: int
    capacity: int
    deltas: tuple[tuple[int, ...], ...]


class Planner:
    """The shortest completion of several visit sequences from the robot's position (under
    ``load``, when given: no point of the order carries more than the capacity)."""

    def __init__(self, metric: Metric, plans: list[tuple[str, ...]], load: Load | None = None):
        self.metric = metric
        self.plans = plans
        self.load = load
        self.memo: dict[tuple, tuple[float, int]] = {}
        self.exact = prod(len(p) + 1 for p in plans) <= MAX_STATES

    def rest(self, idx: tuple[int, ...], cur: str | None) -> float:
        """The least travel to finish every plan from visit indexes ``idx`` at ``cur``
        (INF when the load allows no order)."""
        return self._best(idx, cur)[0]

    def carried(self, idx: tuple[int, ...]) -> int:
        """What the robot carries at visit indexes ``idx``."""
        ld = self.load
        return 0 if ld is None else ld.now + sum(sum(d[:i]) for d, i in zip(ld.deltas, idx,
                                                                           strict=True))

    def fits(self, idx: tuple[int, ...], k: int) -> bool:
        """Whether plan ``k``'s next visit may come at ``idx`` (the load allows it)."""
        ld = self.load
        return ld is None or self.carried(idx) + ld.deltas[k][idx[k]] <= ld.capacity

    def _best(self, idx: tuple[int, ...], cur: str | None) -> tuple[float, int]:
        key = (idx, cur)
        hit = self.memo.get(key)
        if hit is not None:
            return hit
        if not self.exact:
            return self._beam(idx, cur)
        left = [k for k, (p, i) in enumerate(zip(self.plans, idx, strict=True)) if i < len(p)]
        best = (0.0, -1) if not left else (INF, -1)
        for k in left:
            if self.fits(idx, k):
                leg = self.metric.move(cur, self.plans[k][idx[k]])
                total = leg + self._best(_next(idx, k), self.plans[k][idx[k]])[0]
                if total < best[0] - EPS:
                    best = (total, k)
        self.memo[key] = best
        return best

    def _farthest(self, idx: tuple[int, ...], cur: str | None) -> float:
        """A lower bound of the travel left: the distance to the farthest place still to
        be visited (the beam ranks partial orders by what they spent plus this)."""
        return max((self.metric.move(cur, q) for p, i in zip(self.plans, idx, strict=True)
                    for q in p[i:]), default=0.0)

    def _beam(self, idx: tuple[int, ...], cur: str | None) -> tuple[float, int]:
        """The beam search from (``idx``, ``cur``): the shortest complete order found, its
        states memoised along the way (so ``rest`` and the sequence follow that order)."""
        layer: list[tuple[float, tuple[int, ...], tuple[int, ...], str | None]] = \
            [(0.0, (), idx, cur)]
        for _ in range(sum(len(p) - i for p, i in zip(self.plans, idx, strict=True))):
            grown: dict[tuple, tuple] = {}
            for g, path, ix, c in layer:
                for k, (p, i) in enumerate(zip(self.plans, ix, strict=True)):
                    if i < len(p) and self.fits(ix, k):
                        ng, ni = g + self.metric.move(c, p[i]), _next(ix, k)
                        old = grown.get((ni, p[i]))
                        if old is None or ng < old[0] - EPS:
                            grown[(ni, p[i])] = (ng, (*path, k), ni, p[i])
            if not grown:
                self.memo[(idx, cur)] = (INF, -1)
                return self.memo[(idx, cur)]
            layer = sorted(grown.values(), key=lambda s: (s[0] + self._farthest(s[2], s[3]),
                                                          s[0], s[1]))[:MAX_BEAM]
        total, path = layer[0][0], layer[0][1]
        ix, c, spent = idx, cur, 0.0
        for k in path:
            self.memo.setdefault((ix, c), (total - spent, k))
            spent += self.metric.move(c, self.plans[k][ix[k]])
            c, ix = self.plans[k][ix[k]], _next(ix, k)
        self.memo.setdefault((ix, c), (0.0, -1))
        return self.memo[(idx, cur)]

    def total(self) -> float:
        return self.rest(tuple(0 for _ in self.plans), None)


def _next(idx: tuple[int, ...], k: int) -> tuple[int, ...]:
    return idx[:k] + (idx[k] + 1,) + idx[k + 1:]


def merger(metric: Metric, steps: list[tuple[PlanStep, ...]], carry: Carry | None = None
           ) -> Planner:
    """The Planner over the visits of ``steps`` (tail-plans), under ``carry`` if given."""
    vis = [visits(s) for s in steps]
    load = None if carry is None else Load(carry.now, carry.capacity, tuple(
        visit_loads(s, carry.delta) for s in steps))
    return Planner(metric, vis, load)


def choose(metric: Metric, plans: dict[str, tuple[PlanStep, ...]], seq: dict[str, int],
           last: tuple[str, ...], carry: Carry | None = None) -> Choice | None:
    """The next step among the first steps of ``plans`` (task id -> tail-plan, non-empty);
    ``seq``: arrival order of each task; ``last``: the tasks the last action served;
    ``carry``: the load constraint (when no order fits it, the choice is made without)."""
    ids = [t for t in sorted(plans, key=lambda t: seq[t]) if plans[t]]
    if not ids:
        return None
    search = merger(metric, [plans[t] for t in ids], carry)
    vis = search.plans
    zero = tuple(0 for _ in ids)
    first = -2 if search.exact else search._best(zero, None)[1]   # beam: its first visit
    scored = []
    for k, t in enumerate(ids):
        if not vis[k]:
            scored.append((0.0, t))
        elif not search.fits(zero, k) or (first > -2 and k != first):
            scored.append((INF, t))
        else:
            cost = metric.move(None, vis[k][0]) + search.rest(_next(zero, k), vis[k][0])
            scored.append((cost, t))
    low = min(c for c, _ in scored)
    if low == INF and carry is not None:
        return choose(metric, plans, seq, last)
    here = {t for k, t in enumerate(ids) if not vis[k] or metric.move(None, vis[k][0]) < EPS}
    tied = [t for c, t in scored if c <= low + EPS]
    pick = min(tied, key=lambda t: (t not in here, t not in last, -seq[t]))
    k = ids.index(pick)
    now = _served_now(search, k) if vis[k] else {k}
    step = plans[pick][0]
    same = tuple(t for j, t in enumerate(ids) if plans[t][0].actions == step.actions and
                 (step.actions or t == pick) and (j in now or not vis[j]))
    order: list[str] = []
    idx = tuple(0 for _ in ids)
    for j in _sequence(search, k) if vis[k] else ():
        order.append(f"{ids[j]} {vis[j][idx[j]]}")
        idx = _next(idx, j)
    return Choice(plans[same[0]][0], same, round(low, 3), tuple(order))


def _sequence(search: Planner, k: int) -> list[int]:
    """The plans' indexes in the order of least travel that begins with plan ``k``'s visit."""
    zero = tuple(0 for _ in search.plans)
    idx, cur, out = _next(zero, k), search.plans[k][0], [k]
    while True:
        _, j = search._best(idx, cur)
        if j < 0:
            return out
        out.append(j)
        cur = search.plans[j][idx[j]]
        idx = _next(idx, j)


def _served_now(search: Planner, k: int) -> set[int]:
    """The plans whose next visit the order of least travel beginning with plan ``k``'s makes
    at that same place, before moving on: a step they share (a goto) serves those only."""
    seq = _sequence(search, k)
    place, out = search.plans[k][0], {k}
    idx = _next(tuple(0 for _ in search.plans), k)
    for j in seq[1:]:
        if search.plans[j][idx[j]] != place:
            break
        out.add(j)
        idx = _next(idx, j)
    return out


def detour(metric: Metric, top: list[tuple[str, ...]], other: tuple[str, ...]) -> float:
    """How much doing ``other``'s visits along with the ``top`` plans adds to their least
    travel [m] (seed 003, Table 2: compatible-with-top-priority-goal)."""
    return Planner(metric, [*top, other]).total() - Planner(metric, top).total()


def fcfs(metric: Metric, start: str, places: list[tuple[str, ...]]) -> float:
    """The travel [m] of doing each request's places in turn, in arrival order, from
    ``start``: a first-come-first-served robot (seed 003, section 4)."""
    route = [p for ps in places for p in ps]
    return metric.length(start, route)
