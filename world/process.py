"""The world process: the simulation and the clock of a run (docs/bus.md, "The cycle").

    python -m world.process --run RUN --scenario FILE --cycles N --seed S
                            --run-mode lockstep|realtime --out DIR [--resume] [bus flags]

Each cycle is world/cycle.py's CycleRunner (inject, state, agents, apply, step, trace: the
same cycle `teleo simulate` runs in one process) with `BusAgents` as its transport: the events
received on world/events are injected after the scripted ones (a query, as `teleo event`
sends, is answered with the world's verdict), the world state goes out and every agent's
actions come back through bus.clock.Clock, and in lockstep the world keeps pace with the
launch's recorder (BusAgents). The files it keeps in DIR are described in world/recorder.py.
`--resume` (the launcher restarting a world that died) first brings the simulation back to
the cycle the run had reached (world/resume.py), then goes on from there. The agents' memory
the runner keeps goes in the trace at each change, so a restarted world hands back the same.

Exit status: 0 when the cycles are done or a signal stopped it; EXIT_CANNOT_RESUME when a
restart cannot get back to the run's state, EXIT_NOT_READY when the stages did not all
announce themselves in time, EXIT_CANNOT_WRITE when it cannot write its trace or health
record (a full disk: it stops at the cycle it could not record, world/recorder.py) (the
launcher then ends the run with the reason); anything else is a crash, after which the
launcher restarts it with --resume.
"""

from __future__ import annotations

import logging
import threading
import time
from dataclasses import replace
from functools import partial
from itertools import count
from pathlib import Path
from typing import Any

import click

from bus import keys
from bus.clock import Clock, CycleInterrupted
from bus.collector import Collector
from bus.config import BusConfig, bus_options
from bus.cycle import CycleMode, CycleReport
from bus.errors import BusError, NotReady, PaceLost
from bus.messages import EventReply, WorldEvent, WorldState, WorldStatic
from bus.node import Inbox, open_node
from bus.pause import Gate
from bus.pending import PendingQueries, serve_later
from bus.stage import stop_on_signals
from world.changes import Changes
from world.cycle import CycleRunner, CycleState
from world.domain import Domain, World, get_domain
from world.errors import CannotRecord
from world.recorder import CHECKPOINT_EVERY, Recorder
from world.resume import CannotResume, Resumed, can_checkpoint, resume
from world.run_scenario import Scenario, ScenarioError, load_scenario

log = logging.getLogger("teleo.world")
READY_TIMEOUT = 60.0      # [s] for every stage to announce itself
RESTART_TIMEOUT = 30.0    # [s] lockstep waits this long for a crashed stage to come back
STALL_TIMEOUT = 30.0      # [s] lockstep waits this long for a live but silent stage
STALL_REPORT_S = 1.0      # [s] a lockstep cycle waiting longer is recorded as a stall
RECORD_BACKLOG = 8192     # [messages] see record_window
HOLD_REPORT_S = 1.0       # [s] a wait for the record longer than this is in health.jsonl
RECORD_LOST_S = 60.0      # [s] a recorded lockstep run waits this long (times the load) for
                          # a recorder gone or still, then stops: it never runs on unrecorded
EXIT_CANNOT_RESUME = 3
EXIT_NOT_READY = 4
EXIT_CANNOT_WRITE = 5
__all__ = ["pipelines", "run_world"]


def pipelines(agents: list[str]) -> dict[str, list[str]]:
    """Each agent's stages in pipeline order; the goal-entry process feeds every executive."""
    return {a: ["goals", f"{a}.perception", f"{a}.inference", f"{a}.executive"] for a in agents}


def _arrived(events_in: Inbox, asked: PendingQueries, node, t: int):
    """The events the bus brought for cycle `t`, applied after the scripted ones: published on
    world/events, then asked there as queries (`teleo event`), each of which is answered with
    the world's verdict now, before the state of `t` goes out. Every outcome goes in the state
    and the trace (so a run with events stays deterministic and its trace says what
    happened)."""

    def inject(sim: World) -> list[dict[str, Any]]:
        injected = []
        while (msg := events_in.get(0)) is not None:
            if isinstance(msg, WorldEvent):
                injected.append(sim.inject(dict(msg.event)))
        for pending in asked.take():
            event = pending.request.event if isinstance(pending.request, WorldEvent) else None
            if event is None:
                pending.fail(f"expected a WorldEvent, got a {pending.request.KIND}")
                continue
            outcome = sim.inject(dict(event))
            injected.append(outcome)
            pending.answer(EventReply(node.envelope(t), outcome.get("status") == "done",
                                      str(outcome.get("reason", "")), outcome))
        return injected

    return inject


def record_window(agents: int) -> int:
    """[cycles] a lockstep run may be ahead of its recorder: about RECORD_BACKLOG messages
    (at most, a cycle: a world state and its stats, the goal entry's stats, and each agent's
    percepts, beliefs, intention, actions, goal list and its three stages' stats, which go
    alone only from a stage idle after the cycle), an eighth of what the recorder's queue
    holds, so that no sender ever waits for it with messages queued (a process that stops
    drops them: tests/e2e/test_record_drain.py) and its drain at a stop stays short."""
    return max(20, RECORD_BACKLOG // (8 * agents + 3))


class BusAgents:
    """The agents over the bus (world/cycle.py's transport): each state is published and the
    actions collected by bus.clock.Clock; the record's digest and snapshot line of a state,
    and the cycle's young garbage, are done while the agents work on it. In lockstep a state
    does not go out more than `record_window` cycles ahead of what the launch's recorder has
    written whole (its ProcessStats say which), nor the second before the recorder has the
    first (it is sent again while the recorder is awaited): on a loaded machine the run slows
    down rather than lose the end of its record (Clock.keep_pace; no wait when there is no
    recorder, and `recorded`: the run stops rather than outrun it)."""

    def __init__(self, clock: Clock, rec: Recorder, collector: Collector, agents: int,
                 recorded: bool) -> None:
        self.clock, self.rec, self.collector, self.recorded = clock, rec, collector, recorded
        self.pace = record_window(agents) if clock.mode is CycleMode.LOCKSTEP else 0
        self.last: WorldState | None = None   # the last state published
        self.published = 0                    # how many were

    def act(self, cycle: CycleState, snap: dict[str, Any]) -> CycleReport:
        t = cycle.t
        if self.pace and self.published:
            first_out = self.published == 1   # the recorder must have the first state
            held = self.clock.keep_pace(keys.RECORDER, -1 if first_out else t - 1 - self.pace,
                                        resend=self.last if first_out else None,
                                        required_s=RECORD_LOST_S if self.recorded else None)
            if held > HOLD_REPORT_S:
                self.rec.event("record-wait", cycle=t, seconds=round(held, 3))
        state = WorldState(self.clock.node.envelope(t), cycle.snapshot, cycle.outcomes,
                           cycle.events, cycle.memory, cycle.control)   # stamped as it goes
        self.last, self.published = state, self.published + 1
        return self.clock.run_cycle(t, state, meanwhile=partial(self._off_the_path, t, snap))

    def _off_the_path(self, t: int, snap: dict[str, Any]) -> None:
        self.rec.prepare(t, snap)
        self.collector.after_cycle()


def _begin(domain: Domain, scenario: Scenario, seed: int, out: Path, again: bool) -> Resumed:
    """A fresh world at cycle 0, or (`again`) the world of the run recorded in `out`."""
    agents = scenario.agent_ids
    if again:
        return resume(domain, scenario.world_table, seed, agents, out)
    return Resumed(domain.create(scenario.world_table, seed, agents), 0,
                   {a: [] for a in agents}, -1, 0, {a: {} for a in agents})


def run_world(cfg: BusConfig, run: str, scenario: Scenario, cycles: int, seed: int,
              mode: str, out: Path, stop: threading.Event, again: bool = False,
              ready_timeout: float = READY_TIMEOUT, recorded: bool = False) -> bool:
    """Run cycles up to `cycles` (0: until stopped); returns whether all were run.
    `again`: resume the run recorded in `out` (a restarted world); `ready_timeout` [s]: how
    long to wait for every stage (longer when some run on other hosts); `recorded`: the
    launch records the run, so its recorder is waited for at the start and, in lockstep,
    kept pace with as a stage would be (Clock.keep_pace, required): the run stops rather
    than drop cycles from its record (docs/faults.md)."""
    agents = scenario.agent_ids
    domain = get_domain(scenario.domain)
    begun = _begin(domain, scenario, seed, out, again)
    sim, first = begun.world, begun.cycle
    saving = can_checkpoint(sim, domain)
    rec = Recorder(out, scenario.run.render_every, resumed_at=first)
    rec.event("start", cycle=first, resumed=again, checkpoint=begun.checkpoint,
              replayed=begun.replayed, mode=mode)
    if again:
        log.info("resumed at cycle %d (checkpoint %d, %d cycles replayed)", first,
                 begun.checkpoint, begun.replayed)
    start, reason, unwritable, ended = time.monotonic(), "done", None, ""  # ended: episode
    lost = False  # the launch's recorder was lost (PaceLost)
    with open_node(cfg, run, "world") as node:
        events_in = node.subscribe(keys.world_events(run))
        asked = serve_later(node, keys.world_events(run))
        node.declare([keys.stats(run, "world")])
        clock = Clock(node, pipelines(agents), mode=CycleMode(mode),
                      period_s=scenario.run.deadline, deadline_s=STALL_TIMEOUT,
                      restart_timeout_s=RESTART_TIMEOUT, stall_s=STALL_REPORT_S, stop=stop)
        changes = Changes(scenario)  # `teleo program load`, `teleo set` (world/changes.py)
        gate = Gate(node, clock.mode is CycleMode.LOCKSTEP, stop, rec.event, changes.check)
        runner = CycleRunner(sim, agents, scenario.events, begun.outcomes, begun.memory)
        static = WorldStatic(node.envelope(), domain.name, runner.static)
        node.serve(keys.world_static(run),   # sent once a run, and asked
                   lambda _asked: replace(static, env=node.envelope()))
        node.announce()
        collector = Collector()
        transport = BusAgents(clock, rec, collector, len(agents), recorded)
        try:
            clock.wait_ready({p for pipe in pipelines(agents).values() for p in pipe}
                             | ({keys.RECORDER} if recorded else set()), ready_timeout)
            node.publish(keys.world_static(run), static)   # for the record and the view
            rec.event("ready", cycle=first)
            log.info("all stages ready; running cycles %d to %s, %s", first,
                     cycles - 1 if cycles else "unlimited", mode)
            for t in (range(first, cycles) if cycles else count(first)):
                if stop.is_set():
                    reason = "stopped by a signal"
                    break
                gate.hold(t)  # `teleo pause` / `step-run` hold the run here, between cycles
                control = changes.at_cycle(gate.due(t), clock, rec, t)
                done = runner.cycle(t, transport, _arrived(events_in, asked, node, t), control)
                rec.cycle(t, done.snap, done.applied, done.injected, done.report, done.world_ms,
                          done.changed, control)
                node.publish_stats(t, done.world_ms)  # after the report: not a stage of the cycle
                if saving and (t + 1) % CHECKPOINT_EVERY == 0:
                    rec.checkpoint(t + 1, sim.checkpoint(), runner.outcomes)
                if done.over:
                    reason = ended = "the episode is over"
                    break
        except CycleInterrupted as exc:
            reason = f"stopped by a signal ({exc})"
            if exc.stalled:   # a stall in progress at the stop is listed as any other
                rec.event("stalled", cycle=exc.cycle, seconds=round(exc.waited_s, 3),
                          stalled=list(exc.stalled), at_stop=True)
        except CannotRecord as exc:  # a full disk: no cycle runs that nothing records
            reason, unwritable = f"stopped: {exc}", exc
        except PaceLost as exc:      # nor one that the launch's recorder would not record
            reason, lost = f"stopped: {exc}", True
            log.error("%s", reason)
        collector.close()
        asked.close("the run ended before the event could be applied")
        gate.close(rec.cycles)
        # a forever run (or an episode that ended) ends by a stop; one whose recorder
        # was lost did not complete
        completed = (rec.cycles >= cycles if cycles and not ended else True) and not lost
        rec.finish(completed, time.monotonic() - start, reason, runner.memory)
    log.info("stopped after %d cycles (%s): %s", rec.cycles,
             "complete" if completed else "early", reason)
    if unwritable is not None:
        raise unwritable
    return completed


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--scenario", "scenario_file", required=True, type=click.Path(exists=True))
@click.option("--cycles", type=click.IntRange(min=0), default=None, help="0: forever.")
@click.option("--seed", type=int, default=None)
@click.option("--run-mode", type=click.Choice(["lockstep", "realtime"]), default=None)
@click.option("--out", required=True, type=click.Path(file_okay=False), help="Run folder.")
@click.option("--resume", "again", is_flag=True,
              help="Resume the run recorded in --out (a restarted world).")
@click.option("--ready-timeout", type=float, default=READY_TIMEOUT, show_default=True,
              help="Seconds to wait for every stage to announce itself.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help="A field of the scenario changed for this run (world/overrides.py).")
@click.option("--recorded", is_flag=True,
              help="The launch records the run: wait for its recorder and keep pace with it.")
@bus_options
def main(run: str, scenario_file: str, cycles: int | None, seed: int | None,
         run_mode: str | None, out: str, again: bool, ready_timeout: float,
         overrides: tuple[str, ...], recorded: bool, bus_config: BusConfig) -> None:
    """The world process of one run."""
    logging.basicConfig(level=logging.INFO,
                        format="%(asctime)s world %(name)s %(levelname)s %(message)s")
    stop = stop_on_signals(child=True)
    try:
        scenario = load_scenario(scenario_file, overrides)
        run_world(bus_config, run, scenario,
                  scenario.run.cycles if cycles is None else cycles,
                  scenario.run.seed if seed is None else seed,
                  run_mode or scenario.run.mode.value, Path(out), stop, again, ready_timeout,
                  recorded)
    except CannotResume as exc:
        log.error("cannot resume the run: %s", exc)
        raise SystemExit(EXIT_CANNOT_RESUME) from exc
    except NotReady as exc:
        log.error("%s", exc)
        raise SystemExit(EXIT_NOT_READY) from exc
    except CannotRecord as exc:
        log.error("%s", exc)
        raise SystemExit(EXIT_CANNOT_WRITE) from exc
    except (ScenarioError, BusError) as exc:
        log.error("%s", exc)
        raise SystemExit(1) from exc


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
