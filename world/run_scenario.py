"""Scenario files: what `teleo launch` and `teleo simulate` run (docs/scenarios.md).

A scenario is a TOML file with the tables [run], [world], [[agents]], [[goals]] and [[events]].
This module reads the text into frozen dataclasses and checks it, so that a typo is reported
with the file and the field before any process is started. It lives in world/ (below tools/)
because the world process and the goal-entry process read scenarios too. The `[world]` table
names its domain (`domain = "driving"`, the default); the rest of it is the domain's own.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from bus.cycle import CycleMode as Mode
from bus.errors import KeyFormatError
from bus.keys import check_chunk
from world.domain import DEFAULT_DOMAIN, get_domain
from world.errors import ConfigError
from world.overrides import TABLES, Override, OverrideError, apply_overrides, parse_override
from world.registry import names, unknown
from world.scenario_fields import REQUIRED, Errors, at_least, field, is_table, only, shown
from world.scenario_paths import resolve as _resolve
from world.scenario_types import (
    AGENT_STAGES,
    GOAL_OPS,
    RUN_STATUSES,
    AgentSpec,
    RunSettings,
    Scenario,
    ScenarioError,
    ScriptedEvent,
    ScriptedGoal,
)
from world.toml_text import TomlTextError, read_toml

__all__ = ["AGENT_STAGES", "GOAL_OPS", "AgentSpec", "Draft", "RunSettings", "Scenario",
           "ScenarioError", "ScriptedEvent", "ScriptedGoal", "load_scenario", "read_draft",
           "read_document", "scenario_from_dict"]
RUN_FIELDS = ("name", "mode", "cycles", "seed", "deadline", "goals_respawn", "render_every",
              "secure", "status")

def load_scenario(path: str | Path, overrides: Sequence[str] = ()) -> Scenario:
    """Read and check a scenario file, with ``overrides`` (`--set KEY=VALUE` texts,
    world/overrides.py) applied; raises ScenarioError naming the file and field of every
    error (or file:line:col for text that is not UTF-8 or nested too deeply:
    world/toml_text.py)."""
    path = Path(path)
    doc = read_document(path)
    parsed, errors = parse_all(overrides, path)
    doc, wrong = apply_to(doc, path, parsed)
    if errors or wrong:
        raise ScenarioError(*errors, *wrong.values())
    return scenario_from_dict(doc, path, tuple(o.text for o in parsed))


def read_document(path: Path) -> dict[str, Any]:
    """The scenario file's TOML document; raises ScenarioError (world/toml_text.py)."""
    try:
        return read_toml(path)
    except TomlTextError as exc:
        raise ScenarioError(str(exc).replace(": file not found", ": scenario file not found"))\
            from None


def parse_all(overrides: Sequence[str], path: Path) -> tuple[tuple[Override, ...], list[str]]:
    """Each `--set` text that parses, and an error (naming ``path``) for each that does
    not."""
    parsed, errors = [], []
    for text in overrides:
        try:
            parsed.append(parse_override(text))
        except OverrideError as exc:
            errors.append(f"{path}: {exc}")
    return tuple(parsed), errors


def apply_to(doc: dict[str, Any], path: Path, overrides: tuple[Override, ...]
             ) -> tuple[dict[str, Any], dict[Override, str]]:
    """``doc`` with ``overrides`` applied, and the error (naming ``path``) of each that has
    no place in it (left out)."""
    out, errors = apply_overrides(doc, overrides)
    return out, {o: f"{path}: {e}" for o, e in errors.items()}


def scenario_from_dict(doc: dict[str, Any], path: Path, overrides: tuple[str, ...] = ()
                       ) -> Scenario:
    """Check a parsed scenario document (the TOML as a dict); raises ScenarioError with
    every error found."""
    draft = read_draft(doc, path, overrides)
    if draft.errors:
        raise ScenarioError(*draft.errors)
    return draft.scenario


@dataclass(frozen=True)
class Draft:
    """A scenario document read as far as it goes: the scenario (a field in error at its
    default), every error found, and what those errors spoil ("world", "agent ID",
    "goal K" for [[goals]] #K), which the later checks (tools/commands/scenario_check.py) leave out
    rather than report what follows from an error already reported."""

    scenario: Scenario
    errors: tuple[str, ...]
    spoilt: frozenset[str]


def read_draft(doc: dict[str, Any], path: Path, overrides: tuple[str, ...] = ()) -> Draft:
    """Read every table of ``doc``, keeping every error (module world/scenario_fields.py)."""
    errors, spoilt = Errors(path), set()
    only(doc, set(TABLES), "top level", errors)
    run = _run(doc.get("run", {}), errors)
    agents = _agents(doc.get("agents", []), errors, spoilt)
    ids = [a.id for a in agents]
    goals = tuple(_goal(g, i, ids, errors, spoilt)
                  for i, g in enumerate(_array(doc, "goals", errors)))
    events = tuple(e for i, t in enumerate(_array(doc, "events", errors))
                   if (e := _event(t, i, errors)) is not None)
    world = doc.get("world", {})
    before = len(errors)
    if is_table(world, "[world]", errors):
        domain = world.get("domain", DEFAULT_DOMAIN)
        if not isinstance(domain, str) or domain not in names():
            errors.add(unknown(domain, "[world].domain") if isinstance(domain, str) else
                       f"[world].domain: expected one of {list(names())}, got {shown(domain)}")
        else:
            try:                      # a registered world that fails to import: say so here
                get_domain(domain)
            except ConfigError as exc:
                errors.add(str(exc).replace("[world] domain:", "[world].domain:", 1))
    if len(errors) > before:
        spoilt.add("world")
        world = {}
    scenario = Scenario(path, run, world, agents, goals, events, overrides)
    return Draft(scenario, tuple(errors.lines), frozenset(spoilt))


def _array(doc: dict[str, Any], name: str, errors: Errors) -> list[Any]:
    """The array of tables ``name`` ([[agents]], [[goals]], [[events]]); [] when it is not
    one (recorded)."""
    value = doc.get(name, [])
    if isinstance(value, list):
        return value
    errors.add(f"[[{name}]]: expected an array of tables ([[{name}]] entries), "
               f"got {shown(value)}")
    return []


def _run(table: Any, errors: Errors) -> RunSettings:
    where = "[run]"
    if not is_table(table, where, errors):
        return RunSettings()
    only(table, set(RUN_FIELDS), where, errors)
    mode = table.get("mode", "lockstep")
    if not isinstance(mode, str) or mode not in {m.value for m in Mode}:
        errors.add(f"{where}.mode: expected 'lockstep' or 'realtime', got {shown(mode)}")
        mode = "lockstep"
    return RunSettings(
        name=field(table, "name", str, "run", where, errors, (run_name_ok, RUN_NAME_RULE)),
        mode=Mode(mode),
        cycles=field(table, "cycles", int, 100, where, errors, at_least(0)),
        seed=field(table, "seed", int, 0, where, errors),
        deadline=float(field(table, "deadline", (int, float), 0.1, where, errors,
                             at_least(0, strict=True, unit="s"))),
        goals_respawn=field(table, "goals_respawn", int, 3, where, errors, at_least(0)),
        render_every=field(table, "render_every", int, 5, where, errors, at_least(1)),
        secure=field(table, "secure", bool, False, where, errors),
        status=field(table, "status", str, "goals", where, errors,
                     (RUN_STATUSES.__contains__, f"one of {list(RUN_STATUSES)}")),
    )


RUN_NAME_CHARS = 64
RUN_NAME_RULE = (f"a name of at most {RUN_NAME_CHARS} characters without spaces, control "
                 "characters or any of / * $ ? # @ (it names the run's bus keys and folder)")


def run_name_ok(name: str) -> bool:
    """Whether ``name`` can begin a run id (`NAME-xxxxxx`): one chunk of a bus key and the
    name of a folder under the runs folder, never a path out of it."""
    try:
        check_chunk(name, "run name")
    except KeyFormatError:
        return False
    return len(name) <= RUN_NAME_CHARS and name.isprintable()


def _agents(entries: Any, errors: Errors, spoilt: set[str]) -> tuple[AgentSpec, ...]:
    """Every [[agents]] entry whose id could be read (one in error is in ``spoilt``)."""
    agents = []
    for index, table in enumerate(_array({"agents": entries}, "agents", errors)):
        before = len(errors)
        agent = _agent(table, index, errors)
        if agent is not None:
            agents.append(agent)
            if len(errors) > before:
                spoilt.add(f"agent {agent.id}")
    if not agents and not errors.lines:
        errors.add("[[agents]]: expected at least one agent, got none")
    ids = [a.id for a in agents]
    if len(set(ids)) != len(ids):
        errors.add(f"[[agents]]: agent ids must be unique, got {ids}")
    return tuple(agents)


def _agent(table: Any, index: int, errors: Errors) -> AgentSpec | None:
    where = f"[[agents]] #{index + 1}"
    if not is_table(table, where, errors):
        return None
    only(table, {"id", "program", "respawn", "solver", "mechanism"}, where, errors)
    agent_id = field(table, "id", str, REQUIRED, where, errors, (agent_id_ok, AGENT_ID_RULE))
    program = field(table, "program", str, REQUIRED, where, errors)
    respawn = field(table, "respawn", dict, {}, where, errors)
    for stage, count in respawn.items():
        if stage not in AGENT_STAGES or isinstance(count, bool) or not isinstance(count, int) \
                or count < 0:
            errors.add(f"{where}.respawn: expected {{stage = max restarts >= 0}} with stage "
                       f"in {list(AGENT_STAGES)}, got {stage} = {shown(count, 40)}")
    mechanism = field(table, "mechanism", str, "means-ends", where, errors)
    solver = field(table, "solver", bool, True, where, errors)
    if agent_id is None:
        return None
    return AgentSpec(agent_id, _resolve(program, errors.path) if program else Path(""),
                     dict(respawn), solver, mechanism)


AGENT_ID_RULE = "an id without spaces, control characters or any of / * $ ? # @"


def agent_id_ok(agent_id: str) -> bool:
    """Whether ``agent_id`` can name an agent: one chunk of its bus keys and a part of its
    files' names (state-AGENT.json)."""
    try:
        check_chunk(agent_id, "agent id")
    except KeyFormatError:
        return False
    return agent_id.isprintable()


def _goal(table: Any, index: int, agents: list[str], errors: Errors,
          spoilt: set[str]) -> ScriptedGoal:
    """One [[goals]] entry (at its defaults where in error: "goal K" is then spoilt)."""
    where = f"[[goals]] #{index + 1}"
    before = len(errors)
    if not is_table(table, where, errors):
        spoilt.add(f"goal {index + 1}")
        return ScriptedGoal(agent="")
    only(table, {"agent", "goal", "priority", "at_cycle", "op", "goal_id", "force", "once",
                 "deadline"}, where, errors)
    sole = agents[0] if len(agents) == 1 else REQUIRED
    goal = ScriptedGoal(
        agent=field(table, "agent", str, sole, where, errors) or "",
        goal=field(table, "goal", str, "", where, errors),
        priority=field(table, "priority", int, 100, where, errors),
        at_cycle=field(table, "at_cycle", int, 0, where, errors, at_least(0)),
        op=field(table, "op", str, "post", where, errors),
        goal_id=field(table, "goal_id", str, "", where, errors),
        force=field(table, "force", bool, False, where, errors),
        once=field(table, "once", bool, False, where, errors),
        deadline=field(table, "deadline", int, 0, where, errors, at_least(1))
        if "deadline" in table else 0,
    )
    if goal.agent and goal.agent not in agents:
        errors.add(f"{where}.agent: expected one of {agents}, got {shown(goal.agent)}")
    if goal.op not in GOAL_OPS:
        errors.add(f"{where}.op: expected one of {list(GOAL_OPS)}, got {shown(goal.op)}")
    elif goal.op == "post" and not goal.goal:
        errors.add(f"{where}.goal: a post needs the goal text, e.g. '(package-delivered P1)'")
    elif goal.op != "post" and not goal.goal_id:
        errors.add(f"{where}.goal_id: a {goal.op} needs the goal id, e.g. 'g1'")
    if len(errors) > before:
        spoilt.add(f"goal {index + 1}")
    return goal


def _event(table: Any, index: int, errors: Errors) -> ScriptedEvent | None:
    where = f"[[events]] #{index + 1}"
    if not is_table(table, where, errors):
        return None
    at_cycle = field(table, "at_cycle", int, REQUIRED, where, errors, at_least(0))
    event = {k: v for k, v in table.items() if k != "at_cycle"}
    if not event:
        errors.add(f"{where}: expected the event's fields besides at_cycle, got none")
    return ScriptedEvent(at_cycle, event) if at_cycle is not None and event else None
