"""The recorders of a run: a launch's (`run_recorder`, a BusRecorder taking the run off the bus)
and `teleo simulate`'s (`SimRecorder`, the same channels written from its in-process cycle,
tools/commands/simulate.py, so `explain`, `view`, `plot` and `replay` read a simulated run as a
launched one), each with the record's metadata (`record_meta`).
"""

from __future__ import annotations

import json
import secrets
from pathlib import Path
from typing import Any

from bus import keys
from bus.config import BusConfig
from bus.messages import (
    Actions,
    Beliefs,
    Envelope,
    GoalList,
    Intention,
    Message,
    Percepts,
    ProcessStats,
    WorldState,
    WorldStatic,
)
from bus.record import message_record
from tools.records.recorder import BusRecorder
from tools.records.run_record import RECORD_FILE, RecordWriter
from tools.runs import runfile


def run_recorder(cfg: BusConfig, run: str, run_dir: Path, scenario: Any) -> BusRecorder:
    """The launcher's recorder of `run` (not started), writing run_dir/record.mcap. It joins
    the bus as the run's processes do (`cfg`: theirs, with the operator's credentials on a
    secured run): a peer among peers keeps its own links to each of them, so a router that
    dies costs it nothing, as it costs them nothing (a client of the router lost every
    message sent while it was reconnecting: docs/faults.md); a client among
    clients waits for the router with them, and the lockstep world re-sends the cycle it
    waits on, which every stage answers again."""
    return BusRecorder(cfg, run, run_dir / RECORD_FILE, record_meta("launch", scenario),
                       process=keys.RECORDER)


def record_meta(source: str, scenario: Any) -> dict[str, str]:
    """A record's metadata: who wrote it (launch, simulate), of which scenario and domain,
    with which `--set` applied."""
    return {"source": source, "scenario": str(scenario.path), "domain": scenario.domain,
            "overrides": json.dumps(list(scenario.overrides))}


class SimRecorder:
    """The channels of a launch, written from `teleo simulate`'s loop (stats carry the
    in-process compute time of each stage; no goal-entry process, so no stats of one)."""

    def __init__(self, writer: RecordWriter, run: str) -> None:
        self.writer, self.run = writer, run

    @classmethod
    def create(cls, scenario: Any) -> SimRecorder:
        """A recorder writing runs/<name>-sim-<hex>/record.mcap under the runs folder."""
        run = f"{scenario.run.name}-sim-{secrets.token_hex(3)}"
        path = runfile.base_dir() / "runs" / run / RECORD_FILE
        return cls(RecordWriter(path, run, record_meta("simulate", scenario)), run)

    def _add(self, key: str, msg: Message) -> None:
        self.writer.add(key, message_record(key, msg))

    def _env(self, cycle: int, sender: str) -> Envelope:
        return Envelope.now(self.run, cycle, sender)

    def static(self, domain: str, static: dict[str, Any]) -> None:
        """The world's static part, once (a launch's world publishes it at its start)."""
        self._add(keys.world_static(self.run),
                  WorldStatic(self._env(-1, "world"), domain, dict(static)))

    def world(self, cycle: int, snap: dict[str, Any], outcomes: dict[str, list],
              injected: list[dict[str, Any]], memory: dict[str, dict] | None = None) -> None:
        """The world state of `cycle` (outcomes: each agent's of the previous cycle; memory:
        each agent's memory as its last actions sent it, handed back as a launch's world
        does: docs/bus.md, "Agent memory")."""
        self._add(keys.world_state(self.run),
                  WorldState(self._env(cycle, "world"), snap, outcomes, injected,
                             dict(memory or {})))

    def agent(self, cycle: int, agent: str, seen: Any, memory_in: dict | None = None,
              memory_out: dict | None = None) -> None:
        """One agent's percepts, beliefs, intention, actions and stage stats of `cycle`;
        `seen` has percepts, outcomes, beliefs, decision and ms (stage -> compute time);
        `memory_in`: the memory its percepts carry, `memory_out`: what its actions send."""
        run = self.run
        for stage, ms in seen.ms.items():
            process = f"{agent}.{stage}"
            self._add(keys.stats(run, process),
                      ProcessStats(self._env(cycle, process), process, ms, 0))
        self._add(keys.percepts(run, agent), Percepts(
            self._env(cycle, f"{agent}.perception"), agent, tuple(seen.percepts),
            tuple(seen.outcomes), dict(memory_in or {})))
        self._add(keys.beliefs(run, agent), Beliefs(
            self._env(cycle, f"{agent}.inference"), agent,
            tuple(b.to_list() for b in seen.beliefs)))
        env = self._env(cycle, f"{agent}.executive")
        self._add(keys.intention(run, agent), Intention(env, agent, seen.decision.to_dict()))
        self._add(keys.actions(run, agent), Actions(
            env, agent, tuple(a.to_list() for a in seen.decision.actions),
            dict(memory_out or {})))

    def goal_list(self, cycle: int, agent: str, goals: tuple[dict[str, Any], ...]) -> None:
        """The user goals `agent` is given at `cycle`, as the goal-entry process publishes
        them (a cancelled goal leaves the list: tools/records/run_record.py GoalHistory)."""
        self._add(keys.goal_list(self.run, agent), GoalList(self._env(cycle, "goals"), agent,
                                                            goals))

    def world_stats(self, cycle: int, ms: float) -> None:
        self._add(keys.stats(self.run, "world"),
                  ProcessStats(self._env(cycle, "world"), "world", ms, 0))
