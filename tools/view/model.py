"""The web view's memory: fed with records (bus/record.py form) from the bus or a run record,
read by the server's threads. Keeps the last `history` cycles so the page can step back.

    model = ViewModel(run="driving-demo-ab12cd")
    model.add(key, record, size, t_ns)        # from a feed (tools/view/feeds.py)
    model.frame()                             # the newest complete cycle, as the page draws it
    model.frame(213)                          # a past one
    model.status()                            # processes, rates, late counts, goal history
"""

from __future__ import annotations

import threading
from collections import OrderedDict, deque
from dataclasses import dataclass, field
from typing import Any

from bus import keys
from tools.records import GoalHistory
from tools.tree import decision_tree, to_json
from tools.view import scene

RATE_WINDOW_NS = 5_000_000_000  # rates are taken over the last 5 s
TRAIL_STEP_M = 0.5              # a car's trail gets a point each time it has moved this far


@dataclass
class _Cycle:
    time: float
    moving: dict[str, Any]
    agents: dict[str, dict[str, Any]] = field(default_factory=dict)


@dataclass
class _Key:
    count: int = 0
    size: int = 0
    times: deque = field(default_factory=lambda: deque(maxlen=2000))

    def rate(self, now_ns: int) -> float:
        recent = [t for t in self.times if now_ns - t <= RATE_WINDOW_NS]
        span = (recent[-1] - recent[0]) / 1e9 if len(recent) > 1 else 0.0
        return (len(recent) - 1) / span if span > 0 else 0.0


class ViewModel:
    """Thread-safe: a feed thread adds, server threads read; `changed` wakes the readers."""

    def __init__(self, run: str | None = None, history: int = 5000, source: str = "") -> None:
        self.run, self.history_len, self.source = run, history, source
        self.changed = threading.Condition()
        self.version = 0
        self.cycles: OrderedDict[int, _Cycle] = OrderedDict()
        self.map: dict[str, Any] | None = None
        self._static: dict[str, Any] = {}
        self.trails: dict[str, list[tuple[int, float, float]]] = {}
        self.goals = GoalHistory()
        self.keys: dict[str, _Key] = {}
        self.stats: dict[str, dict[str, Any]] = {}
        self.alive: frozenset[str] | None = None   # None: no liveliness (a record file)
        self.incarnations: dict[str, int] = {}
        self.agents: set[str] = set()

    def add(self, key: str, record: dict[str, Any], size: int = 0, t_ns: int = 0) -> None:
        """Take one record; a record of another run than the one followed is ignored."""
        run = record["env"]["run"]
        with self.changed:
            if self.run is None:
                self.run = run
            if run != self.run:
                return
            stat = self.keys.setdefault(key.split("/", 2)[-1], _Key())
            stat.count, stat.size = stat.count + 1, size
            stat.times.append(t_ns)
            self._take(key, record)
            self.version += 1
            self.changed.notify_all()

    def _take(self, key: str, record: dict[str, Any]) -> None:
        kind, cycle = record["kind"], record["env"]["cycle"]
        if kind == "WorldState":
            self._world(cycle, record["snapshot"])
        elif kind == "ProcessStats":
            self.stats[record["process"]] = {"compute_ms": record["compute_ms"],
                                             "late": record["late"], "cycle": cycle}
        elif kind in ("Intention", "Percepts") and cycle in self.cycles:
            agent = keys.agent_of_key(key) or record.get("agent", "")
            self.agents.add(agent)
            slot = self.cycles[cycle].agents.setdefault(agent, {})
            if kind == "Intention":
                slot["decision"] = record["decision"]
                self.goals.feed(record)
            else:
                slot["self"] = record.get("self", {})

    def _world(self, cycle: int, snapshot: dict[str, Any]) -> None:
        static, moving = scene.split(snapshot)
        if static != self._static or self.map is None:
            self._static, self.map = static, scene.map_of(snapshot)
        self.cycles[cycle] = _Cycle(float(snapshot.get("time", 0.0)), moving)
        while len(self.cycles) > self.history_len:
            self.cycles.popitem(last=False)
        for car in snapshot.get("cars", ()):
            if car.get("kind") == "agent":
                trail = self.trails.setdefault(car["id"], [])
                if not trail or abs(trail[-1][1] - car["x"]) + abs(trail[-1][2] - car["y"]) \
                        >= TRAIL_STEP_M or trail[-1][0] > cycle:
                    trail.append((cycle, car["x"], car["y"]))

    def set_presence(self, alive: frozenset[str], incarnations: dict[str, int]) -> None:
        with self.changed:
            self.alive, self.incarnations = alive, incarnations

    # -- reading ---------------------------------------------------------------------
    def newest(self) -> int | None:
        """The newest cycle every known agent has decided (else the newest world state)."""
        with self.changed:
            for cycle in reversed(self.cycles):
                if all("decision" in self.cycles[cycle].agents.get(a, {}) for a in self.agents):
                    return cycle
            return next(reversed(self.cycles), None)

    def frame(self, cycle: int | None = None) -> dict[str, Any] | None:
        """One cycle as the page draws it: the world's moving parts, each agent's goals,
        decision tree, actions and self percept, and the trails up to that cycle."""
        cycle = self.newest() if cycle is None else cycle
        with self.changed:
            c = self.cycles.get(cycle) if cycle is not None else None
            if c is None:
                return None
            agents = {}
            for agent in sorted(self.agents):
                slot = c.agents.get(agent, {})
                decision = slot.get("decision")
                agents[agent] = {
                    "self": slot.get("self", {}),
                    "goals": decision.get("goals", []) if decision else [],
                    "actions": decision.get("actions", []) if decision else [],
                    "tree": to_json(decision_tree(decision, f"{agent}, cycle {cycle}"))
                    if decision else None}
            trails = {a: [[x, y] for k, x, y in pts if k <= cycle]
                      for a, pts in self.trails.items()}
            return {"run": self.run, "cycle": cycle, "time": c.time, "world": c.moving,
                    "map_id": self.map["id"] if self.map else "", "agents": agents,
                    "trails": trails}

    def status(self, now_ns: int) -> dict[str, Any]:
        """Processes (liveliness, appearances, compute, late), key rates, cycles held and
        each agent's goal status changes (for the timeline)."""
        with self.changed:
            names = set(self.stats) | set(self.incarnations) | set(self.alive or ())
            procs = [{"name": n, "up": None if self.alive is None else n in self.alive,
                      "appeared": self.incarnations.get(n, 0), **self.stats.get(n, {})}
                     for n in sorted(names)]
            rates = [{"key": k, "count": s.count, "bytes": s.size,
                      "rate": round(s.rate(now_ns), 1)} for k, s in sorted(self.keys.items())]
            first = next(iter(self.cycles), None)
            last = next(reversed(self.cycles), None)
            return {"run": self.run, "source": self.source, "first": first, "last": last,
                    "processes": procs, "keys": rates, "goals": dict(self.goals.changes),
                    "map_id": self.map["id"] if self.map else ""}

    def snapshots_for_render(self, cycle: int) -> list[dict[str, Any]]:
        """Whole snapshot dicts up to `cycle` (every 10th, and that one) for a PNG render."""
        with self.changed:
            picked = [k for k in self.cycles if k <= cycle and (k % 10 == 0 or k == cycle)]
            return [{**self._static, **self.cycles[k].moving} for k in picked]
