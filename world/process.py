"""The world process: the simulation and the clock of a run (DESIGN.md, One cognitive cycle).

    python -m world.process --run RUN --scenario FILE --cycles N --seed S
                            --run-mode lockstep|realtime --out DIR [bus flags]

For cycle t: inject the events due (scripted at t, or received on world/events), publish the
world state of t with each agent's action outcomes of t-1, collect every agent's actions of
t through bus.clock.Clock, apply them and step the physics by dt. It writes in DIR:
trace.jsonl (one line per cycle: cycle, actions per agent, counters, a digest of the state,
the outcomes of injected events; nothing that depends on timing, so two lockstep runs with
one seed give the same file),
snapshots.jsonl (every render_every cycles and the last, for world.driving.render) and
world-final.json (counters, late and dead stages, timing, each agent's last memory) for the
launcher's summary. Each agent's memory (what its executive sends with its actions: world-model
facts, SCS threads and discount factors) is kept and handed back in the next world state, so
a restarted agent process loses none of it (docs/bus.md, "Agent memory").
"""

from __future__ import annotations

import hashlib
import json
import logging
import signal
import threading
import time
from collections import Counter
from itertools import count
from pathlib import Path
from typing import Any

import click

from bus import keys
from bus.clock import Clock
from bus.config import BusConfig, bus_options
from bus.cycle import CycleMode, CycleReport
from bus.messages import WorldEvent, WorldState
from bus.node import Inbox, open_node
from world.domain import get_domain
from world.run_scenario import Scenario, load_scenario

log = logging.getLogger("teleo.world")
READY_TIMEOUT = 60.0      # [s] for every stage to announce itself
RESTART_TIMEOUT = 30.0    # [s] lockstep waits this long for a crashed stage to come back
STALL_TIMEOUT = 30.0      # [s] lockstep waits this long for a live but silent stage


def pipelines(agents: list[str]) -> dict[str, list[str]]:
    """Each agent's stages in pipeline order; the goal-entry process feeds every executive."""
    return {a: ["goals", f"{a}.perception", f"{a}.inference", f"{a}.executive"] for a in agents}


def digest(snapshot: dict[str, Any]) -> str:
    """A short hash of the whole world state (canonical JSON)."""
    text = json.dumps(snapshot, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


class Recorder:
    """The files of the run folder and the totals for world-final.json."""

    def __init__(self, out: Path, render_every: int) -> None:
        out.mkdir(parents=True, exist_ok=True)
        self.out = out
        self.render_every = render_every
        self.trace = (out / "trace.jsonl").open("w", buffering=1)  # lines
        self.snaps = (out / "snapshots.jsonl").open("w")
        self.late: Counter[str] = Counter()
        self.dead: Counter[str] = Counter()
        self.noop: Counter[str] = Counter()
        self.stage_ms: Counter[str] = Counter()
        self.cycle_ms = 0.0
        self.world_ms = 0.0
        self.cycles = 0
        self.last_snapshot: dict[str, Any] | None = None
        self.last_written = -1

    def cycle(self, t: int, snap: dict[str, Any], injected: list[dict[str, Any]],
              report: CycleReport, world_ms: float) -> None:
        line = {"cycle": t, "actions": {a: [list(x) for x in acts]
                                        for a, acts in sorted(report.actions.items())},
                "counters": snap["counters"], "digest": digest(snap)}
        if injected:
            line["events"] = injected
        self.trace.write(json.dumps(line, sort_keys=True) + "\n")
        self.late.update(report.late)
        self.dead.update(report.dead)
        self.noop.update(report.noop)
        self.stage_ms.update(report.stage_ms)
        self.cycle_ms += report.elapsed_ms
        self.world_ms += world_ms
        self.cycles = t + 1
        self.last_snapshot = snap
        if t % self.render_every == 0:
            self._snapshot(t, snap)

    def _snapshot(self, t: int, snap: dict[str, Any]) -> None:
        self.snaps.write(json.dumps(snap) + "\n")
        self.last_written = t

    def finish(self, completed: bool, elapsed_s: float, memory: dict[str, Any]) -> None:
        if self.last_snapshot is not None and self.last_written != self.cycles - 1:
            self._snapshot(self.cycles - 1, self.last_snapshot)
        self.trace.close()
        self.snaps.close()
        final = {
            "completed": completed, "cycles": self.cycles, "elapsed_s": elapsed_s,
            "late": dict(self.late), "dead": dict(self.dead), "noop": dict(self.noop),
            "counters": (self.last_snapshot or {}).get("counters", {}),
            "timing_ms": {"cycle": self.cycle_ms, "world": self.world_ms,
                          "stages": dict(self.stage_ms)},
            "memory": memory,
        }
        tmp = self.out / "world-final.json.tmp"
        tmp.write_text(json.dumps(final, indent=1))
        tmp.replace(self.out / "world-final.json")


def _drain(inbox: Inbox) -> list[dict[str, Any]]:
    events = []
    while (msg := inbox.get(0)) is not None:
        if isinstance(msg, WorldEvent):
            events.append(dict(msg.event))
    return events


def _actions_of(sim, agent: str, actions: tuple, noop: tuple[str, ...]) -> list[list[Any]]:
    """The agent's actions of this cycle, or the world's safe action when they did not arrive
    (a dead or late stage): an uncontrolled agent is stopped, never left on its last controls."""
    if agent in noop:
        return sim.safe_actions(agent)
    return [list(x) for x in actions]


def run_world(cfg: BusConfig, run: str, scenario: Scenario, cycles: int, seed: int,
              mode: str, out: Path, stop: threading.Event) -> bool:
    """Run `cycles` cycles (0: until stopped); returns whether all were run."""
    agents = scenario.agent_ids
    sim = get_domain(scenario.domain).create(scenario.world_table, seed, agents)
    scripted: dict[int, list[dict[str, Any]]] = {}
    for e in scenario.events:
        scripted.setdefault(e.at_cycle, []).append(e.event)
    rec = Recorder(out, scenario.run.render_every)
    with open_node(cfg, run, "world") as node:
        events_in = node.subscribe(keys.world_events(run))
        clock = Clock(node, pipelines(agents), mode=CycleMode(mode),
                      period_s=scenario.run.deadline, deadline_s=STALL_TIMEOUT,
                      restart_timeout_s=RESTART_TIMEOUT)
        node.announce()
        expected = {p for pipe in pipelines(agents).values() for p in pipe}
        clock.wait_ready(expected, READY_TIMEOUT)
        log.info("all %d stages ready; running %s cycles, %s", len(expected),
                 cycles or "unlimited", mode)
        outcomes: dict[str, list] = {a: [] for a in agents}
        memory: dict[str, dict] = {a: {} for a in agents}
        start = time.monotonic()
        for t in (range(cycles) if cycles else count()):
            if stop.is_set():
                break
            w0 = time.perf_counter()
            injected = [sim.inject(e) for e in scripted.get(t, []) + _drain(events_in)]
            snap = sim.snapshot_dict()
            world_ms = (time.perf_counter() - w0) * 1e3
            report = clock.run_cycle(t, WorldState(node.envelope(t), snap, outcomes, injected,
                                                   dict(memory)))
            memory.update(report.memory)   # an agent given the no-op keeps its last memory
            w0 = time.perf_counter()
            outcomes = {a: sim.apply_actions(a, _actions_of(sim, a, acts, report.noop))
                        for a, acts in report.actions.items()}
            sim.step()
            rec.cycle(t, snap, injected, report, world_ms + (time.perf_counter() - w0) * 1e3)
        completed = rec.cycles == cycles if cycles else True  # a forever run ends by a stop
        rec.finish(completed, time.monotonic() - start, memory)
    log.info("stopped after %d cycles (%s)", rec.cycles, "complete" if completed else "early")
    return completed


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--scenario", "scenario_file", required=True, type=click.Path(exists=True))
@click.option("--cycles", type=click.IntRange(min=0), default=None, help="0: forever.")
@click.option("--seed", type=int, default=None)
@click.option("--run-mode", type=click.Choice(["lockstep", "realtime"]), default=None)
@click.option("--out", required=True, type=click.Path(file_okay=False), help="Run folder.")
@bus_options
def main(run: str, scenario_file: str, cycles: int | None, seed: int | None,
         run_mode: str | None, out: str, bus_config: BusConfig) -> None:
    """The world process of one run."""
    logging.basicConfig(level=logging.INFO,
                        format="%(asctime)s world %(name)s %(levelname)s %(message)s")
    scenario = load_scenario(scenario_file)
    stop = threading.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        signal.signal(sig, lambda *_: stop.set())
    run_world(bus_config, run, scenario,
              scenario.run.cycles if cycles is None else cycles,
              scenario.run.seed if seed is None else seed,
              run_mode or scenario.run.mode.value, Path(out), stop)


if __name__ == "__main__":
    main()
