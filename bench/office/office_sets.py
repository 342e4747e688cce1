"""Random office request sets (seed 003) and what bench/office/office.py measures of each: run
through the ROGUE planner in one process (tools/commands/simulate.py: the pymunk office world, its
perception, the engine), the travel of the executed order by the map, against serving the
requests first come, first served and against the optimal order.

A set: the robot in a room of the default floor, 3 to 8 delivery requests of one priority,
each an item (mail, fax or memo) held by a person, to a room or to another person, posted at
a cycle of its own. Each request has two visits, its holder's room (acquire) and where the
item goes (deliver), or one when they are the same room.

The optimal order is found by branch and bound over every order of the visits that keeps
each request's own order (pickup before delivery) and its arrival (a visit starts only once
its request has arrived, by the robot's own timing: 1 m/s, 7 cycles an acquire or a
delivery; the robot waits only when no arrived request has a visit left: a robot that waited
for every request would need least travel and serve late), never carrying more than the
robot's capacity. The bound is the exact least travel of the remaining visits with the
arrivals relaxed (an exact search of its own, class Relaxed), so a branch is cut only when
it cannot beat the best order found: the result is exact (the table says so per set)."""

from __future__ import annotations

import random
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from agents.lang import load_program
from agents.lang.core.store import PerceptIndex
from agents.lang.engine import as_percepts
from agents.lang.planning.domain import Domain, Metric
from tools.commands.simulate import SimRun, simulate
from world.domain import get_domain
from world.office.config import DEFAULT_NORTH, DEFAULT_PEOPLE, DEFAULT_SOUTH, OfficeConfig
from world.run_scenario import scenario_from_dict

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = ROOT / "programs" / "office_rogue.tlp"
ROOMS = tuple(r.id for r in (*DEFAULT_SOUTH, *DEFAULT_NORTH))
PEOPLE = {p.id: p.room for p in DEFAULT_PEOPLE}
KINDS = ("mail", "fax", "memo")
CONFIG = OfficeConfig()
CYCLES_PER_M = 1.0 / (CONFIG.speed * CONFIG.dt)              # [cycles/m]
STEP_CYCLES = round(CONFIG.handover / CONFIG.dt) + 1          # [cycles] an acquire or deliver
MAX_CYCLES = 8000        # a set's run ends by then at the latest [cycles]
MAX_NODES = 3_000_000    # orders searched before the optimum is reported unproven [nodes]
INF = float("inf")


@dataclass(frozen=True)
class Request:
    """``item`` (of ``kind``) held by ``holder``, to ``to`` (a room or a person), posted at
    cycle ``arrival``."""

    item: str
    kind: str
    holder: str
    to: str
    arrival: int

    @property
    def goal(self) -> str:
        return f"(delivered {self.item} {self.to})"

    def visits(self) -> tuple[str, ...]:
        """The rooms it needs, in its own order (one when they are the same)."""
        pick, drop = PEOPLE[self.holder], PEOPLE.get(self.to, self.to)
        return (pick,) if pick == drop else (pick, drop)


@dataclass(frozen=True)
class RequestSet:
    seed: int
    start: str
    requests: tuple[Request, ...]


def random_set(seed: int, low: int = 3, high: int = 8, window: int = 240) -> RequestSet:
    """A set drawn with random.Random(seed): ``low``..``high`` requests, the first at cycle 0,
    the others at cycles in [0, ``window``]; random holders, kinds and destinations (half of
    them rooms, half people)."""
    rng = random.Random(seed)
    n = rng.randint(low, high)
    arrivals = sorted([0] + [rng.randint(0, window) for _ in range(n - 1)])
    out = []
    for k, at in enumerate(arrivals):
        holder = rng.choice(sorted(PEOPLE))
        kind = rng.choice(KINDS)
        to = rng.choice([r for r in ROOMS if r != PEOPLE[holder]]) if rng.random() < 0.5 \
            else rng.choice([p for p in sorted(PEOPLE) if p != holder])
        out.append(Request(f"{kind}-{holder}-{k + 1}", kind, holder, to, at))
    return RequestSet(seed, rng.choice(ROOMS), tuple(out))


def scenario(s: RequestSet):
    """The set as a scenario (as its TOML would say)."""
    doc = {"run": {"name": f"office-set-{s.seed}", "mode": "lockstep", "cycles": MAX_CYCLES,
                   "seed": 1},
           "world": {"domain": "office", "robots": [{"agent": "ME", "room": s.start}],
                     "items": [{"id": r.item, "kind": r.kind, "holder": r.holder, "to": r.to}
                               for r in s.requests]},
           "agents": [{"id": "ME", "program": str(PROGRAM), "mechanism": "rogue"}],
           "goals": [{"agent": "ME", "goal": r.goal, "priority": 5, "at_cycle": r.arrival}
                     for r in s.requests]}
    return scenario_from_dict(doc, ROOT / "bench" / "office" / f"office-set-{s.seed}.toml")


def run_set(s: RequestSet) -> SimRun:
    """The set run through the planner until every request has ended (or MAX_CYCLES)."""
    n = len(s.requests)

    def done(states) -> bool:
        return len(states["ME"].planner.finished) >= n
    return simulate(scenario(s), MAX_CYCLES, until=done)


@lru_cache(maxsize=1)
def metric() -> Metric:
    """Distances of the default floor by the world's own percepts (those between rooms do
    not depend on where the robot is)."""
    domain = get_domain("office")
    raw = domain.perceive(domain.create({}, 1, ["ME"]).snapshot_dict(), "ME")
    return Metric(Domain(load_program(PROGRAM)).travel, PerceptIndex(as_percepts(raw)))


@dataclass(frozen=True)
class Measured:
    """One set: travel [m] by the map of teleo's executed order, first-come-first-served,
    the optimal order (and whether the search finished: ``proven``), and the order of least
    travel that ignores arrivals (a robot that knew every request at the start and waited);
    ``done_once``: requests achieved with none of their steps executed twice."""

    teleo: float
    fcfs: float
    optimal: float
    proven: bool
    clairvoyant: float
    done_once: int
    requests: int
    cycles: int


def measure(s: RequestSet, run: SimRun, m: Metric, optimum: bool = True) -> Measured:
    """The figures of one set's run (``optimum``: search the optimal order too; else it is
    reported as first-come-first-served's, unproven)."""
    ps = run.states["ME"].planner
    achieved = {f.goal_id for f in ps.finished if f.status == "achieved"}
    seen: dict[tuple[str, str], int] = {}
    for a in ps.head:
        if a.result in ("verified", "applied"):
            for t in a.tasks:
                seen[(t, a.step)] = seen.get((t, a.step), 0) + 1
    twice = {t for (t, _), n in seen.items() if n > 1}
    best, proven = optimal(s, m) if optimum else (fcfs(s, m), False)
    return Measured(m.length(s.start, list(ps.travel.route)), fcfs(s, m), best, proven,
                    clairvoyant(s, m), len(achieved - twice), len(s.requests),
                    len(run.records))


def fcfs(s: RequestSet, m: Metric) -> float:
    """Each request served whole, in arrival order."""
    order = sorted(s.requests, key=lambda r: r.arrival)
    return m.length(s.start, [p for r in order for p in r.visits()])


class Relaxed:
    """The least travel of the remaining visits with the arrivals relaxed (each request's own
    order and the capacity kept): an exact memoised search over the orders, written here
    apart from the planner's own (agents/lang/planning/merge.py) so that the yardstick does
    not share code with what it measures."""

    def __init__(self, s: RequestSet, m: Metric):
        self.m = m
        self.plans = [r.visits() for r in s.requests]
        self.memo: dict[tuple, float] = {}

    def load(self, idx: tuple[int, ...]) -> int:
        return sum(1 for p, i in zip(self.plans, idx, strict=True) if len(p) == 2 and i == 1)

    def rest(self, idx: tuple[int, ...], here: str) -> float:
        key = (idx, here)
        if key not in self.memo:
            best, held = (0.0 if all(i == len(p) for p, i in zip(self.plans, idx,
                                                               strict=True)) else INF), \
                self.load(idx)
            for k, (p, i) in enumerate(zip(self.plans, idx, strict=True)):
                if i < len(p) and not (len(p) == 2 and i == 0 and held >= CONFIG.capacity):
                    nxt = idx[:k] + (i + 1,) + idx[k + 1:]
                    best = min(best, self.m.between(here, p[i]) + self.rest(nxt, p[i]))
            self.memo[key] = best
        return self.memo[key]


def clairvoyant(s: RequestSet, m: Metric) -> float:
    """The least travel when arrivals do not matter (every order of the visits, in each
    request's own order, within the capacity)."""
    return Relaxed(s, m).rest(tuple(0 for _ in s.requests), s.start)


def optimal(s: RequestSet, m: Metric) -> tuple[float, bool]:
    """The least travel of an order that respects arrivals (see the top), by branch and
    bound; (travel, proven: the search ended within MAX_NODES)."""
    reqs = s.requests
    plans = [r.visits() for r in reqs]
    bound = Relaxed(s, m)
    best = [fcfs(s, m) + 1e-6]   # first come, first served is such an order
    nodes = [0]

    def go(idx: tuple[int, ...], here: str, now: float, travel: float, load: int) -> None:
        nodes[0] += 1
        if nodes[0] > MAX_NODES or travel + bound.rest(idx, here) >= best[0] - 1e-6:
            return
        left = [k for k in range(len(reqs)) if idx[k] < len(plans[k])]
        if not left:
            best[0] = travel
            return
        ready = [k for k in left if reqs[k].arrival <= now]
        if not ready:   # nothing to do: wait for the next request
            now = min(reqs[k].arrival for k in left)
            ready = [k for k in left if reqs[k].arrival <= now]
        moves = []
        for k in ready:
            delta = 1 if idx[k] == 0 and len(plans[k]) == 2 else -1 if idx[k] == 1 else 0
            if load + delta <= CONFIG.capacity:
                moves.append((m.between(here, plans[k][idx[k]]), k, delta))
        for leg, k, delta in sorted(moves):
            nxt = idx[:k] + (idx[k] + 1,) + idx[k + 1:]
            steps = 2 if len(plans[k]) == 1 else 1
            go(nxt, plans[k][idx[k]], now + leg * CYCLES_PER_M + steps * STEP_CYCLES,
               travel + leg, load + delta)
    go(tuple(0 for _ in reqs), s.start, 0.0, 0.0, 0)
    return round(min(best[0], fcfs(s, m)), 3), nodes[0] <= MAX_NODES
