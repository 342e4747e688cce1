"""What a scenario file holds, as frozen dataclasses (world/run_scenario.py reads them)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from bus.cycle import CycleMode
from world.domain import DEFAULT_DOMAIN
from world.errors import WorldError
from world.scenario_paths import world_files

AGENT_STAGES = ("perception", "inference", "executive")
GOAL_OPS = ("post", "cancel", "priority")


class ScenarioError(WorldError):
    """A scenario file that cannot be run; one message per error (``errors``), each naming
    the file and the field."""

    def __init__(self, *errors: str) -> None:
        super().__init__("\n".join(errors))
        self.errors = tuple(errors)


@dataclass(frozen=True)
class RunSettings:
    """The [run] table. cycles 0 means forever; deadline [s] is the realtime period per cycle;
    secure: run on a secured bus (TLS, a user per process, access control: docs/bus.md)."""

    name: str = "run"
    mode: CycleMode = CycleMode.LOCKSTEP
    cycles: int = 100
    seed: int = 0
    deadline: float = 0.1
    goals_respawn: int = 3
    render_every: int = 5
    secure: bool = False
    status: str = "goals"   # what fails a run: RUN_STATUSES (docs/faults.md)


RUN_STATUSES = {
    "goals": "a goal that could not be kept fails the run, as a fault of the system does",
    "system": "only a fault of the system fails the run; a goal not kept is reported",
}


@dataclass(frozen=True)
class AgentSpec:
    """One [[agents]] entry: its id, program, how often each of its processes may restart,
    and the mechanism that answers an impasse: ``mechanism`` names it (default
    "means-ends", the problem solver of seed 000; "rogue", the planner of seed 003;
    agents.lang.engine.SOLVERS); ``solver = false``: none, the executive alone."""

    id: str
    program: Path
    respawn: dict[str, int] = field(default_factory=dict)
    solver: bool = True
    mechanism: str = "means-ends"

    @property
    def impasse_handler(self) -> str | None:
        """The SOLVERS name to give the Engine, or None for the executive alone."""
        return self.mechanism if self.solver else None

    def max_restarts(self, stage: str) -> int:
        """Restarts allowed for `stage` (perception, inference, executive)."""
        return self.respawn.get(stage, 3)


@dataclass(frozen=True)
class ScriptedGoal:
    """One [[goals]] entry: a user request applied by the goal-entry process at `at_cycle`."""

    agent: str
    goal: str = ""
    priority: int = 100
    at_cycle: int = 0
    op: str = "post"
    goal_id: str = ""
    force: bool = False  # rank above the program's goals, or cancel an achieved goal
    once: bool = False   # a post: dropped when achieved, not kept
    deadline: int = 0    # a post: failed unless achieved within this many cycles (0: none)


@dataclass(frozen=True)
class ScriptedEvent:
    """One [[events]] entry: a world event dict injected before the state of `at_cycle`."""

    at_cycle: int
    event: dict[str, Any]


@dataclass(frozen=True)
class Scenario:
    """A whole scenario file, checked."""

    path: Path
    run: RunSettings
    world: dict[str, Any]
    agents: tuple[AgentSpec, ...]
    goals: tuple[ScriptedGoal, ...]
    events: tuple[ScriptedEvent, ...]
    overrides: tuple[str, ...] = ()  # the `--set KEY=VALUE` applied (world/overrides.py)

    @property
    def domain(self) -> str:
        """The `[world] domain` name (world/domain.py registry)."""
        return str(self.world.get("domain", DEFAULT_DOMAIN))

    @property
    def world_table(self) -> dict[str, Any]:
        """The `[world]` table without its `domain` key: the domain's own configuration
        (a `*_file` path found as a program is, beside the scenario first)."""
        return world_files({k: v for k, v in self.world.items() if k != "domain"}, self.path)

    @property
    def agent_ids(self) -> list[str]:
        return [a.id for a in self.agents]

    def agent(self, agent_id: str) -> AgentSpec:
        for spec in self.agents:
            if spec.id == agent_id:
                return spec
        raise ScenarioError(f"{self.path}: no agent {agent_id!r} (agents: {self.agent_ids})")
