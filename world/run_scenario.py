"""Scenario files: what `teleo launch` and `teleo simulate` run (docs/scenarios.md).

A scenario is a TOML file with the tables [run], [world], [[agents]], [[goals]] and [[events]].
This module reads the text into frozen dataclasses and checks it, so that a typo is reported
with the file and the field before any process is started. It lives in world/ (below tools/)
because the world process and the goal-entry process read scenarios too. The `[world]` table
names its domain (`domain = "driving"`, the default); the rest of it is the domain's own.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from bus.cycle import CycleMode as Mode
from world.domain import DEFAULT_DOMAIN, DOMAINS
from world.errors import WorldError
from world.toml_text import TomlTextError, read_toml

AGENT_STAGES = ("perception", "inference", "executive")
GOAL_OPS = ("post", "cancel", "priority")


class ScenarioError(WorldError):
    """A scenario file that cannot be run; the message names the file and the field."""


@dataclass(frozen=True)
class RunSettings:
    """The [run] table. cycles 0 means forever; deadline [s] is the realtime period per cycle;
    secure: run on a secured bus (TLS, a user per process, access control: docs/bus.md)."""

    name: str = "run"
    mode: Mode = Mode.LOCKSTEP
    cycles: int = 100
    seed: int = 0
    deadline: float = 0.1
    goals_respawn: int = 3
    render_every: int = 5
    secure: bool = False


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

    @property
    def domain(self) -> str:
        """The `[world] domain` name (world/domain.py registry)."""
        return str(self.world.get("domain", DEFAULT_DOMAIN))

    @property
    def world_table(self) -> dict[str, Any]:
        """The `[world]` table without its `domain` key: the domain's own configuration."""
        return {k: v for k, v in self.world.items() if k != "domain"}

    @property
    def agent_ids(self) -> list[str]:
        return [a.id for a in self.agents]

    def agent(self, agent_id: str) -> AgentSpec:
        for spec in self.agents:
            if spec.id == agent_id:
                return spec
        raise ScenarioError(f"{self.path}: no agent {agent_id!r} (agents: {self.agent_ids})")


def load_scenario(path: str | Path) -> Scenario:
    """Read and check a scenario file; raises ScenarioError naming the file and field (or
    file:line:col for text that is not UTF-8 or nested too deeply: world/toml_text.py)."""
    path = Path(path)
    try:
        doc = read_toml(path)
    except TomlTextError as exc:
        raise ScenarioError(str(exc).replace(": file not found", ": scenario file not found"))\
            from None
    return scenario_from_dict(doc, path)


def scenario_from_dict(doc: dict[str, Any], path: Path) -> Scenario:
    """Check a parsed scenario document (the TOML as a dict)."""
    _only(doc, {"run", "world", "agents", "goals", "events"}, path, "top level")
    run = _run(doc.get("run", {}), path)
    agents = tuple(_agent(a, i, path) for i, a in enumerate(doc.get("agents", [])))
    if not agents:
        raise ScenarioError(f"{path}: [[agents]]: expected at least one agent, got none")
    ids = [a.id for a in agents]
    if len(set(ids)) != len(ids):
        raise ScenarioError(f"{path}: [[agents]]: agent ids must be unique, got {ids}")
    goals = tuple(_goal(g, i, path, ids) for i, g in enumerate(doc.get("goals", [])))
    events = tuple(_event(e, i, path) for i, e in enumerate(doc.get("events", [])))
    world = doc.get("world", {})
    if not isinstance(world, dict):
        raise ScenarioError(f"{path}: [world]: expected a table, got {type(world).__name__}")
    domain = world.get("domain", DEFAULT_DOMAIN)
    if domain not in DOMAINS:
        raise ScenarioError(f"{path}: [world].domain: expected one of {list(DOMAINS)}, "
                            f"got {domain!r}")
    return Scenario(path, run, world, agents, goals, events)


def _only(table: dict[str, Any], allowed: set[str], path: Path, where: str) -> None:
    unknown = sorted(set(table) - allowed)
    if unknown:
        raise ScenarioError(
            f"{path}: {where}: unknown field(s) {unknown}; expected {sorted(allowed)}")


def _typed(table: dict[str, Any], key: str, kind: type | tuple, default: Any, where: str) -> Any:
    value = table.get(key, default)
    if isinstance(value, bool) or not isinstance(value, kind):
        raise ScenarioError(f"{where}.{key}: expected {_kind_name(kind)}, got {value!r}")
    return value


def _kind_name(kind: type | tuple) -> str:
    kinds = kind if isinstance(kind, tuple) else (kind,)
    return " or ".join(k.__name__ for k in kinds)


def _run(table: dict[str, Any], path: Path) -> RunSettings:
    where = f"{path}: [run]"
    _only(table, {"name", "mode", "cycles", "seed", "deadline", "goals_respawn", "render_every",
                  "secure"}, path, "[run]")
    mode = table.get("mode", "lockstep")
    if mode not in {m.value for m in Mode}:
        raise ScenarioError(f"{where}.mode: expected 'lockstep' or 'realtime', got {mode!r}")
    settings = RunSettings(
        name=_typed(table, "name", str, "run", where),
        mode=Mode(mode),
        cycles=_typed(table, "cycles", int, 100, where),
        seed=_typed(table, "seed", int, 0, where),
        deadline=float(_typed(table, "deadline", (int, float), 0.1, where)),
        goals_respawn=_typed(table, "goals_respawn", int, 3, where),
        render_every=_typed(table, "render_every", int, 5, where),
        secure=_flag(table, "secure", where),
    )
    if settings.cycles < 0 or settings.deadline <= 0 or settings.render_every < 1:
        raise ScenarioError(f"{where}: expected cycles >= 0, deadline > 0 [s], render_every >= 1")
    return settings


def _flag(table: dict[str, Any], key: str, where: str) -> bool:
    value = table.get(key, False)
    if not isinstance(value, bool):
        raise ScenarioError(f"{where}.{key}: expected true or false, got {value!r}")
    return value


def _agent(table: dict[str, Any], index: int, path: Path) -> AgentSpec:
    where = f"{path}: [[agents]] #{index + 1}"
    _only(table, {"id", "program", "respawn", "solver", "mechanism"}, path,
          f"[[agents]] #{index + 1}")
    agent_id = _typed(table, "id", str, None, where)
    program = _resolve(_typed(table, "program", str, None, where), path)
    respawn = _typed(table, "respawn", dict, {}, where)
    for stage, count in respawn.items():
        if stage not in AGENT_STAGES or isinstance(count, bool) or not isinstance(count, int):
            raise ScenarioError(
                f"{where}.respawn: expected {{stage = max restarts}} with stage in "
                f"{list(AGENT_STAGES)}, got {stage} = {count!r}")
    mechanism = _typed(table, "mechanism", str, "means-ends", where)
    return AgentSpec(agent_id, program, dict(respawn), _bool(table, "solver", where, True),
                     mechanism)


def _bool(table: dict[str, Any], key: str, where: str, default: bool = False) -> bool:
    value = table.get(key, default)
    if not isinstance(value, bool):
        raise ScenarioError(f"{where}.{key}: expected true or false, got {value!r}")
    return value


def _resolve(program: str, scenario_path: Path) -> Path:
    """A relative program path is looked up beside the scenario, then in each folder above
    it (so `programs/driving.tlp` in scenarios/x.toml finds the repository's programs/ from
    any working directory), then in the working directory."""
    candidate = Path(program)
    if candidate.is_absolute():
        return candidate
    for folder in scenario_path.resolve().parents:
        try:
            if (folder / candidate).exists():
                return folder / candidate
        except (OSError, ValueError):  # a name too long to look up, a NUL byte: not there
            return candidate
    return candidate


def _goal(table: dict[str, Any], index: int, path: Path, agents: list[str]) -> ScriptedGoal:
    where = f"{path}: [[goals]] #{index + 1}"
    _only(table, {"agent", "goal", "priority", "at_cycle", "op", "goal_id", "force"},
          path, f"[[goals]] #{index + 1}")
    goal = ScriptedGoal(
        agent=_typed(table, "agent", str, agents[0] if len(agents) == 1 else None, where),
        goal=_typed(table, "goal", str, "", where),
        priority=_typed(table, "priority", int, 100, where),
        at_cycle=_typed(table, "at_cycle", int, 0, where),
        op=_typed(table, "op", str, "post", where),
        goal_id=_typed(table, "goal_id", str, "", where),
        force=_bool(table, "force", where),
    )
    if goal.agent not in agents:
        raise ScenarioError(f"{where}.agent: expected one of {agents}, got {goal.agent!r}")
    if goal.op not in GOAL_OPS:
        raise ScenarioError(f"{where}.op: expected one of {list(GOAL_OPS)}, got {goal.op!r}")
    if goal.op == "post" and not goal.goal:
        raise ScenarioError(
            f"{where}.goal: a post needs the goal text, e.g. '(package-delivered P1)'")
    if goal.op != "post" and not goal.goal_id:
        raise ScenarioError(f"{where}.goal_id: a {goal.op} needs the goal id, e.g. 'g1'")
    if goal.at_cycle < 0:
        raise ScenarioError(f"{where}.at_cycle: expected >= 0, got {goal.at_cycle}")
    return goal


def _event(table: dict[str, Any], index: int, path: Path) -> ScriptedEvent:
    where = f"{path}: [[events]] #{index + 1}"
    at_cycle = _typed(table, "at_cycle", int, None, where)
    event = {k: v for k, v in table.items() if k != "at_cycle"}
    if not event:
        raise ScenarioError(f"{where}: expected the event's fields besides at_cycle, got none")
    return ScriptedEvent(at_cycle, event)
