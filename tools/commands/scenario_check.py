"""Checking a whole scenario before anything runs: the world table against its domain, every
agent's program (and its actions against those the world knows), every scripted goal against
its agent's program and every scripted event's kind. `teleo check SCENARIO`, `teleo launch`
and `teleo simulate` all call `check_scenario`, so a mistake is one line naming the file and
the field, never a crash 10 s into a run."""

from __future__ import annotations

import difflib
import re
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import click

from agents.lang import Engine, GoalError, ProgramError, load_program
from agents.lang.core.conjunction import goal_literals
from agents.lang.core.program import Program
from agents.lang.engine import SOLVERS
from agents.lang.reading.goals import parse_goal
from agents.processes.goal_store import MAX_ID_CHARS, MAX_PRIORITY
from agents.processes.goal_texts import rank_problem
from world.domain import get_domain
from world.errors import WorldError
from world.overrides import Override
from world.run_scenario import (
    AgentSpec,
    Draft,
    Scenario,
    ScenarioError,
    ScriptedGoal,
    apply_to,
    parse_all,
    read_document,
    read_draft,
)


def check_scenario(scenario: Scenario) -> dict[str, Program]:
    """Check ``scenario`` fully; return each agent's loaded program. Raises ScenarioError
    with every error found (each names the file and what is wrong; a program's diagnostics
    in full)."""
    programs, errors = _checks(scenario, frozenset())
    if errors:
        raise ScenarioError(*errors)
    return programs


def _checks(scenario: Scenario, spoilt: frozenset[str]) -> tuple[dict[str, Program], list[str]]:
    """Each agent's program and every error of the checks, leaving out what ``spoilt``
    names (run_scenario.Draft: an entry whose own fields are in error)."""
    where, errors = scenario.path, []
    domain = get_domain(scenario.domain)
    if "world" not in spoilt:
        try:
            domain.check_config(scenario.world_table, scenario.agent_ids)
        except WorldError as exc:   # a line each (the table's other errors too)
            errors += [f"{where}: {line}" for line in str(exc).splitlines()]
    programs: dict[str, Program] = {}
    for agent in scenario.agents:
        if f"agent {agent.id}" not in spoilt:
            # a [world] in error is read as the default world: its actions would mislead
            known = domain.actions if "world" not in spoilt else ()
            problem = _agent_problem(agent, domain.name, known, programs)
            if problem:
                errors.append(f"{where}: agent {agent.id}: {problem}")
    checked = [(k, g) for k, g in enumerate(scenario.goals) if f"goal {k + 1}" not in spoilt]
    for k, goal in checked:
        if goal.agent in programs:
            problem = _goal_problem(goal, programs[goal.agent])
            if problem:
                errors.append(f"{where}: [[goals]] #{k + 1}: {problem}")
    for k, goal in enumerate(scenario.goals):   # in error elsewhere: its text alone
        if f"goal {k + 1}" in spoilt and goal.op == "post" and goal.goal:
            try:
                parse_goal(goal.goal)
            except GoalError as exc:
                errors.append(f"{where}: [[goals]] #{k + 1}: {exc}")
    if len(checked) == len(scenario.goals):  # the ids g1, g2, ... count every post
        errors += _goal_id_problems(scenario)
    for k, event in enumerate(scenario.events):
        kind = event.event.get("kind")
        if domain.event_kinds and kind not in domain.event_kinds:
            errors.append(f"{where}: [[events]] #{k + 1}.kind: expected one of "
                          f"{list(domain.event_kinds)}, got {kind!r}")
            continue
        problem = domain.check_event(event.event) if domain.check_event else ""
        if problem:   # a field of the wrong type, out of range, or unknown to its kind
            errors.append(f"{where}: [[events]] #{k + 1} ({kind}): {problem}")
    return programs, errors


def _agent_problem(agent: AgentSpec, domain: str, known: tuple[str, ...],
                   programs: dict[str, Program]) -> str:
    """What is wrong with one agent's mechanism and program ("" if nothing), ``known`` the
    actions its world knows (none: not checked); its program, loaded, is added to
    ``programs``."""
    if agent.mechanism not in SOLVERS:
        return f"mechanism: expected one of {list(SOLVERS)}, got {agent.mechanism!r}"
    if not _is_file(Path(agent.program)):
        return f"program {agent.program} not found"
    try:
        programs[agent.id] = load_program(str(agent.program))
    except ProgramError as exc:
        return f"program {agent.program}:\n{exc}"
    return _unknown_action(programs[agent.id], domain, known)


def _goal_id_problems(scenario: Scenario) -> list[str]:
    """A scripted cancel or priority change must name a goal the scenario has posted by then:
    the goal-entry process gives posts the ids g1, g2, ... in the order it runs them (by cycle,
    then file order); a request naming no such goal would be refused at run time, a line in
    a log."""
    posted: list[str] = []
    problems = []
    order = sorted(enumerate(scenario.goals), key=lambda kg: (kg[1].at_cycle, kg[0]))
    for k, goal in order:
        if goal.op == "post":
            posted.append(f"g{len(posted) + 1}")
        elif goal.goal_id not in posted:
            known = ", ".join(posted) if posted else "none"
            problems.append(f"{scenario.path}: [[goals]] #{k + 1}: goal_id {goal.goal_id!r}: "
                            f"the scenario has posted no such goal by cycle {goal.at_cycle} "
                            f"(its posts get g1, g2, ... in order; by then: {known})")
    return problems


def _unknown_action(program: Program, domain: str, known: tuple[str, ...]) -> str:
    """The first action of ``program`` its world does not know ("" if none, or if the
    domain does not say what it knows): the world would fail it every time it is sent."""
    for action in program.actions():
        if known and action.name not in known:
            return (f"{action.loc}: action {action.name} is not one the {domain} world knows "
                    f"({' '.join(known)})")
    return ""


def _goal_problem(goal: ScriptedGoal, program: Program) -> str:
    """What is wrong with one scripted request ("" if nothing): the goal against the
    agent's program, the priority range and the priority rule (goal_texts.rank_problem),
    the goal id's length."""
    if goal.op != "cancel" and not 1 <= goal.priority <= MAX_PRIORITY:
        return f"priority: expected an integer in 1..{MAX_PRIORITY}, got {goal.priority}"
    if len(goal.goal_id) > MAX_ID_CHARS:
        return f"goal_id: longer than {MAX_ID_CHARS} characters"
    if goal.op == "post":
        engine = Engine(program)
        try:
            engine.add_goal(engine.initial_state(), goal.goal, priority=goal.priority)
        except GoalError as exc:
            return _with_suggestion(str(exc), program)
    if goal.op != "cancel" and not goal.force:
        problem = rank_problem(tuple(str(g.literal) for g in program.goals), goal.priority)
        if problem:
            return f"{problem} (force = true)"
    return ""


def goal_warnings(scenario: Scenario) -> list[str]:
    """A warning (without the file's name) for each scripted goal that names an object (a
    symbol, not a number nor a variable) which neither the world as it starts nor the
    agent's program names anywhere:
    the agent would wait for a percept of it, then fail (`(delivered fax-jhm r-5399)`
    where there is no r-5399). A warning, not an error: a world may
    bring an object later, and a test may post such a goal on purpose."""
    posts = [(k, g) for k, g in enumerate(scenario.goals) if g.op == "post" and g.goal]
    if not posts:
        return []
    domain = get_domain(scenario.domain)
    try:
        snap = domain.create(scenario.world_table, scenario.run.seed,
                             scenario.agent_ids).snapshot_dict()
    except WorldError:
        return []   # reported as an error of the world table
    known = set(_strings(snap)) | set(scenario.agent_ids)
    texts = {a.id: set(re.findall(r"[^\s()]+", _text(Path(a.program))))
             for a in scenario.agents}
    out = []
    for k, goal in posts:
        try:
            literals = goal_literals(parse_goal(goal.goal))
        except GoalError:
            continue   # an error of its own
        names = [a for lit in literals for a in lit.args if isinstance(a, str)]
        for name in dict.fromkeys(names):
            if name not in known and name not in texts.get(goal.agent, set()):
                out.append(f"[[goals]] #{k + 1}: goal {goal.goal}: no object "
                           f"{name!r} in the {domain.name} world as it starts, nor in "
                           f"{goal.agent}'s program (the goal would wait for a percept of "
                           "it, then fail)")
    return out


def _strings(value: Any) -> Any:
    """Every string in a snapshot (keys and values, at any depth)."""
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for k, v in value.items():
            yield from _strings(k)
            yield from _strings(v)
    elif isinstance(value, list | tuple):
        for v in value:
            yield from _strings(v)


def _text(path: Path) -> str:
    try:
        return path.read_text(errors="replace")
    except OSError:
        return ""


def _with_suggestion(message: str, program: Program) -> str:
    """``message`` with "did you mean" for an undefined concept close to one the program
    has, as a program's own errors have it."""
    found = re.search(r"undefined concept '([^']+)'", message)
    if not found or "did you mean" in message:
        return message
    names = sorted(program.concepts)
    close = difflib.get_close_matches(found.group(1), names, n=1)
    return f"{message} (did you mean '{close[0]}'?)" if close else message


def _is_file(path: Path) -> bool:
    """Whether `path` is a file; a path the system cannot even look up (too long, a NUL
    byte) is not one."""
    try:
        return path.is_file()
    except (OSError, ValueError):
        return False


def load_checked(path: str | Path, overrides: Sequence[str] = ()
                 ) -> tuple[Scenario, dict[str, Program]]:
    """The scenario in ``path`` with ``overrides`` (`--set KEY=VALUE`, world/overrides.py)
    applied, checked as ``check_scenario`` checks it, and each agent's program. Raises
    ScenarioError with every error: of the overrides themselves (not KEY=VALUE, no such
    place), of the file and of the checks; an error only the overrides bring is said to
    come from the one that brings it, else from them all:
    `s.toml: --set run.cycles=-5: [run].cycles: expected >= 0, got -5`."""
    path = Path(path)
    doc = read_document(path)
    parsed, errors = parse_all(overrides, path)
    changed, wrong = apply_to(doc, path, parsed)
    fitting = tuple(o for o in parsed if o not in wrong)
    draft, programs, found = _everything(changed, path, tuple(o.text for o in parsed))
    if found and fitting:
        found = _attributed(found, doc, path, fitting)
    if errors or wrong or found:
        raise ScenarioError(*errors, *wrong.values(), *found)
    return draft.scenario, programs


def _everything(doc: dict[str, Any], path: Path, overrides: tuple[str, ...] = ()
                ) -> tuple[Draft, dict[str, Program], list[str]]:
    """The document read (run_scenario.read_draft) and checked, with every error."""
    draft = read_draft(doc, path, overrides)
    programs, errors = _checks(draft.scenario, draft.spoilt)
    return draft, programs, [*draft.errors, *errors]


def _attributed(errors: list[str], doc: dict[str, Any], path: Path,
                overrides: tuple[Override, ...]) -> list[str]:
    """``errors`` with each one the file alone does not have said to come from the
    override that alone brings it, else from all of them together."""
    own = set(_everything(doc, path)[2])
    alone = [set(_everything(apply_to(doc, path, (o,))[0], path)[2]) for o in overrides]
    prefix = f"{path}: "
    out = []
    for error in errors:
        if error in own:
            out.append(error)
            continue
        by = [o.label for o, found in zip(overrides, alone, strict=True) if error in found] \
            or [o.label for o in overrides]
        rest = error[len(prefix):] if error.startswith(prefix) else error
        out.append(f"{prefix}{', '.join(by)}: {rest}")
    return out

override_option = click.option(
    "--set", "overrides", multiple=True, metavar="KEY=VALUE",
    help="Change a field of the scenario for this run, checked as the file is: "
         "run.cycles=300, world.pedestrians=20, agents.ME.program=programs/x.tlp "
         "(docs/scenarios.md, \"Overrides\"); repeatable.")
"""`--set KEY=VALUE` of `teleo launch`, `simulate` and `check` (world/overrides.py)."""


def check_learned(scenario: Scenario, learned: str) -> None:
    """Refuse a learned file that does not fit every agent's program, before any process
    starts (the message names file:line:col, e.g. a concept the program does not define),
    and an empty one, as `teleo check` refuses it (launch and simulate must not take
    a file check refuses; a run's learned file is never empty, its first line names
    its program). `teleo launch --learned` and `teleo simulate --learned` call it."""
    from agents.lang import LangError
    from agents.lang.loader import read_text
    from agents.lang.registry import read_learned

    try:
        text = read_text(learned)
        if not text.strip():
            raise click.ClickException(
                f"{learned}:1:1: the file is empty: expected learned skills as a run writes "
                f"them (learned-AGENT.tlp, its first line naming the program; "
                f"teleo check PROGRAM {learned})")
        for agent in scenario.agents:
            read_learned(load_program(agent.program), text, learned)
    except LangError as exc:
        raise click.ClickException(str(exc)) from exc
