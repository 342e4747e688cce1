"""The web view's memory: fed with records (bus/record.py form) from the bus or a run record,
read by the server's threads. Keeps the last `history` cycles so the page can step back.

    model = ViewModel(run="driving-demo-ab12cd")
    model.add(key, record, size, t_ns)        # from a feed (tools/view/feeds.py)
    model.frame()                             # the newest complete cycle, as the page draws it
    model.frame(213)                          # a past one
    model.status(now_ns)                      # the run's state, processes, rates, goal history

Each agent's percepts and beliefs of a cycle are kept as JSON bytes (a few KB a cycle) and
read again only for a frame, whose beliefs panel (beliefs.py) works out why each unsatisfied
goal is false; a goal that failed stays in the goal table of every later cycle.
"""

from __future__ import annotations

import logging
import threading
import time
from collections import OrderedDict, deque
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

import orjson

from agents.lang import LangError
from bus import keys
from bus.stats import record_stats
from tools.records.run_record import GoalHistory
from tools.records.tree import Node, decision_tree, to_json
from tools.view import scene
from tools.view.beliefs import listing, why
from tools.view.programs import Programs
from world.static import has_static

log = logging.getLogger(__name__)
MALFORMED = (LangError, TypeError, ValueError, KeyError, IndexError, AttributeError)
"""What reading a malformed percept, belief or decision of a record raises."""
RATE_WINDOW_NS = 5_000_000_000  # rates are taken over the last 5 s
TRAIL_STEP_M = 0.5              # a car's trail gets a point each time it has moved this far
QUIET_S = 5.0                   # [s] a run without liveliness tokens that sent nothing for
                                # this long has ended (a replay played to its end)


class RunState(StrEnum):
    """What the page's badge says about the run it shows."""

    WAITING = "waiting"   # live, nothing received yet
    LIVE = "live"         # its processes are up (or, without liveliness, it is sending)
    ENDED = "ended"       # no process of it is up any more (or it has gone quiet)
    RECORD = "record"     # a run record file: every cycle at once, nothing live


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
        self.told: dict[str, Any] | None = None   # the world's static part (world/static)
        self.wants_static = False   # a world state came without it: the feed asks for it
        self.trails: dict[str, list[tuple[int, float, float]]] = {}
        self.goals = GoalHistory()
        self.keys: dict[str, _Key] = {}
        self.stats: dict[str, dict[str, Any]] = {}
        self.alive: frozenset[str] | None = None   # None: no liveliness (a record file)
        self.incarnations: dict[str, int] = {}
        self.agents: set[str] = set()
        self.programs = Programs()
        self.recorded = False           # fed from a record file, not from the bus
        self.last_message: float | None = None  # [s, monotonic] when a record last came

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
            self.last_message = time.monotonic()
            self.version += 1
            self.changed.notify_all()

    def _take(self, key: str, record: dict[str, Any]) -> None:
        kind, cycle = record["kind"], record["env"]["cycle"]
        if kind == "WorldState":
            self._world(cycle, record["snapshot"])
        elif kind == "WorldStatic":
            self.told, self.wants_static = dict(record.get("static") or {}), False
        for process, at, ms, late in record_stats(record, own=True):  # alone or carried
            self.stats[process] = {"compute_ms": ms, "late": late, "cycle": at}
        if kind in ("Intention", "Percepts", "Beliefs") and cycle in self.cycles:
            agent = keys.agent_of_key(key) or record.get("agent", "")
            self.agents.add(agent)
            slot = self.cycles[cycle].agents.setdefault(agent, {})
            if kind == "Intention":
                if not isinstance(record["decision"], dict):
                    raise TypeError(f"Intention.decision: expected a map, got "
                                    f"{type(record['decision']).__name__}")
                self.goals.feed(record)
                slot["decision"] = record["decision"]
                self.programs.saw(agent, record["decision"])
            elif kind == "Beliefs":
                slot["beliefs"] = orjson.dumps(record.get("beliefs", []))
            else:
                slot["self"] = record.get("self", {})
                if record.get("program"):   # a program swapped in (teleo program load)
                    self.programs.swap(agent, cycle, record["program"])
                memory = record.get("memory")
                model = memory.get("model", []) if isinstance(memory, dict) else []
                slot["percepts"] = orjson.dumps([record.get("percepts", []), model])

    def _world(self, cycle: int, snapshot: dict[str, Any]) -> None:
        if not has_static(snapshot):   # sent once a run: until known, not shown
            if self.told is None:
                self.wants_static = True
                return
            snapshot = {**self.told, **snapshot}
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

    def past_goals(self, agent: str, records: Any) -> None:
        """The goal store's list of ``agent`` (records.GoalHistory.ended_before): the goals
        that ended before the view opened join the goal table and the timeline."""
        with self.changed:
            for record in records if isinstance(records, tuple | list) else ():
                if isinstance(record, dict):
                    self.goals.ended_before(agent, record)
            self.version += 1
            self.changed.notify_all()

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
        """One cycle as the page draws it: the world's moving parts, each agent's goals (the
        ones that failed before it too), decision tree, actions, self percept and beliefs
        panel, and the trails up to that cycle."""
        cycle = self.newest() if cycle is None else cycle
        with self.changed:
            c = self.cycles.get(cycle) if cycle is not None else None
            if c is None:
                return None
            slots = {a: dict(c.agents.get(a, {})) for a in sorted(self.agents)}
            before = self.cycles.get(cycle - 1)
            for a, slot in slots.items():  # the world model the agent inferred with
                prior = before.agents.get(a, {}).get("decision") if before else None
                slot["prior_model"] = _scs_model(prior)
            failed = {a: self._failed_before(a, cycle) for a in slots}
            trails = {a: [[x, y] for k, x, y in pts if k <= cycle]
                      for a, pts in self.trails.items()}
            head = {"run": self.run, "cycle": cycle, "time": c.time, "world": c.moving,
                    "map_id": self.map["id"] if self.map else ""}
        agents = {a: self._agent(a, cycle, slot, failed[a]) for a, slot in slots.items()}
        return {**head, "agents": agents, "trails": trails}

    def _agent(self, agent: str, cycle: int, slot: dict[str, Any],
               failed: list[dict[str, Any]]) -> dict[str, Any]:
        decision = slot.get("decision")
        goals = decision.get("goals", []) if decision else []
        listed = {g.get("id") for g in goals}
        try:
            tree = to_json(decision_tree(decision, f"{agent}, cycle {cycle}")) \
                if decision else None
        except MALFORMED as exc:  # a record is only shape-checked (bus/record.py)
            tree = to_json(Node("decision", f"{agent}, cycle {cycle}: the decision does not "
                                            f"read: {exc!r}"))
        return {"self": slot.get("self", {}),
                "goals": goals + [g for g in failed if g["id"] not in listed],
                "actions": decision.get("actions", []) if decision else [],
                "tree": tree, "why": self._why(agent, cycle, slot)}

    def _failed_before(self, agent: str, cycle: int) -> list[dict[str, Any]]:
        """The goals of `agent` whose status at `cycle` is failed (from their history: the
        executive drops a failed goal from its list), each with the reason it failed."""
        out = []
        for gid, changes in self.goals.changes.get(agent, {}).items():
            last = next((ch for ch in reversed(changes) if ch["cycle"] <= cycle), None)
            if last is not None and last["status"] == "failed":
                out.append({"id": gid, "goal": last["goal"], "priority": last["priority"],
                            "status": "failed", "note": last["note"], "bindings": {},
                            "instance": "", "failed_at": last["cycle"]})
        return out

    def _why(self, agent: str, cycle: int, slot: dict[str, Any]) -> dict[str, Any] | None:
        """The beliefs panel of one agent's cycle (None when its beliefs are not held)."""
        if "beliefs" not in slot or "decision" not in slot:
            return None
        beliefs = orjson.loads(slot["beliefs"])
        percepts, model = orjson.loads(slot["percepts"]) if "percepts" in slot else ([], [])
        model = model or slot["prior_model"]  # a simulate record echoes no agent memory
        program, source = self.programs.get(agent, cycle)
        if program is None:
            try:
                return {"error": source, "goals": [], "path": [], **listing(beliefs)}
            except MALFORMED as exc:
                return {"error": f"{source}; the beliefs do not read: {exc!r}", "goals": [],
                        "path": [], "count": 0, "beliefs": []}
        try:
            panel = why(program, slot["decision"], percepts, beliefs)
            warning = self.programs.differs(source, program, percepts, model, beliefs) \
                if percepts else "no percepts recorded for this cycle"
        except MALFORMED as exc:  # a record is only shape-checked (bus/record.py)
            log.warning("view: %s cycle %s not explained: %r", agent, cycle, exc)
            return {"error": f"this cycle's records do not read: {exc!r}", "goals": [],
                    "path": [], "count": len(beliefs), "beliefs": []}
        return {"program": source, "warning": warning, **panel}

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
            state, why_state = self.state()
            return {"run": self.run, "source": self.source, "first": first, "last": last,
                    "state": state.value, "state_note": why_state,
                    "processes": procs, "keys": rates, "goals": dict(self.goals.changes),
                    "map_id": self.map["id"] if self.map else ""}

    def state(self) -> tuple[RunState, str]:
        """The run's state for the badge, and what it is judged by."""
        if self.recorded:
            return RunState.RECORD, "a run record: every cycle of it is held"
        if self.alive is not None:
            if self.alive:
                return RunState.LIVE, f"{len(self.alive)} process(es) of the run up"
            return RunState.ENDED, "no process of the run is up any more"
        if self.last_message is None:
            return RunState.WAITING, "nothing received yet"
        quiet = time.monotonic() - self.last_message
        if quiet < QUIET_S:
            return RunState.LIVE, "messages arriving (the run has no liveliness tokens)"
        return RunState.ENDED, f"no message for {quiet:.0f} s (and no liveliness tokens)"

    def snapshots_for_render(self, cycle: int) -> list[dict[str, Any]]:
        """Whole snapshot dicts up to `cycle` (every 10th, and that one) for a PNG render."""
        with self.changed:
            picked = [k for k in self.cycles if k <= cycle and (k % 10 == 0 or k == cycle)]
            return [{**self._static, **self.cycles[k].moving} for k in picked]


def _scs_model(decision: Any) -> list:
    """The world model (SCS facts, seed 002) an agent held after a decision: what it sent
    with its actions, so what its inference used the next cycle; [] when none."""
    section = decision.get("scs") if isinstance(decision, dict) else None
    model = section.get("model") if isinstance(section, dict) else None
    return model if isinstance(model, list) else []
