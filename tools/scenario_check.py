"""Checking a whole scenario before anything runs: the world table against its domain, every
agent's program (and its actions against those the world knows), every scripted goal against
its agent's program and every scripted event's kind. `teleo check SCENARIO`, `teleo launch`
and `teleo simulate` all call `check_scenario`, so a mistake is one line naming the file and
the field, never a crash 10 s into a run."""

from __future__ import annotations

from pathlib import Path

from agents.lang import Engine, GoalError, ProgramError, load_program
from agents.lang.engine import SOLVERS
from agents.lang.program import Program
from agents.processes.goal_store import MAX_ID_CHARS, MAX_PRIORITY, rank_problem
from world.domain import get_domain
from world.errors import WorldError
from world.run_scenario import Scenario, ScenarioError, ScriptedGoal, load_scenario


def check_scenario(scenario: Scenario) -> dict[str, Program]:
    """Check ``scenario`` fully; return each agent's loaded program. Raises ScenarioError
    (the message names the file and what is wrong; a program's diagnostics in full)."""
    where = scenario.path
    domain = get_domain(scenario.domain)
    try:
        domain.check_config(scenario.world_table, scenario.agent_ids)
    except WorldError as exc:
        raise ScenarioError(f"{where}: {exc}") from None
    programs: dict[str, Program] = {}
    for agent in scenario.agents:
        if agent.mechanism not in SOLVERS:
            raise ScenarioError(f"{where}: agent {agent.id}: mechanism: expected one of "
                                f"{list(SOLVERS)}, got {agent.mechanism!r}")
        if not _is_file(Path(agent.program)):
            raise ScenarioError(f"{where}: agent {agent.id}: program {agent.program} not found")
        try:
            programs[agent.id] = load_program(str(agent.program))
        except ProgramError as exc:
            raise ScenarioError(f"{where}: agent {agent.id}: program {agent.program}:\n{exc}") \
                from None
        problem = _unknown_action(programs[agent.id], domain.name, domain.actions)
        if problem:
            raise ScenarioError(f"{where}: agent {agent.id}: {problem}")
    for k, goal in enumerate(scenario.goals):
        problem = _goal_problem(goal, programs[goal.agent])
        if problem:
            raise ScenarioError(f"{where}: [[goals]] #{k + 1}: {problem}")
    _check_goal_ids(scenario)
    for k, event in enumerate(scenario.events):
        kind = event.event.get("kind")
        if domain.event_kinds and kind not in domain.event_kinds:
            raise ScenarioError(f"{where}: [[events]] #{k + 1}.kind: expected one of "
                                f"{list(domain.event_kinds)}, got {kind!r}")
        problem = domain.check_event(event.event) if domain.check_event else ""
        if problem:   # a field of the wrong type, out of range, or unknown to its kind
            raise ScenarioError(f"{where}: [[events]] #{k + 1} ({kind}): {problem}")
    return programs


def _check_goal_ids(scenario: Scenario) -> None:
    """A scripted cancel or priority change must name a goal the scenario has posted by then:
    the goal-entry process gives posts the ids g1, g2, ... in the order it runs them (by cycle,
    then file order); a request naming no such goal would be refused at run time, a line in
    a log."""
    posted: list[str] = []
    order = sorted(enumerate(scenario.goals), key=lambda kg: (kg[1].at_cycle, kg[0]))
    for k, goal in order:
        if goal.op == "post":
            posted.append(f"g{len(posted) + 1}")
        elif goal.goal_id not in posted:
            known = ", ".join(posted) if posted else "none"
            raise ScenarioError(f"{scenario.path}: [[goals]] #{k + 1}: goal_id {goal.goal_id!r}:"
                                f" the scenario has posted no such goal by cycle "
                                f"{goal.at_cycle} (its posts get g1, g2, ... in order; by "
                                f"then: {known})")


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
    agent's program, the priority range and the priority rule (goal_store.rank_problem),
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
            return str(exc)
    if goal.op != "cancel" and not goal.force:
        problem = rank_problem(tuple(str(g.literal) for g in program.goals), goal.priority)
        if problem:
            return f"{problem} (force = true)"
    return ""


def _is_file(path: Path) -> bool:
    """Whether `path` is a file; a path the system cannot even look up (too long, a NUL
    byte) is not one."""
    try:
        return path.is_file()
    except (OSError, ValueError):
        return False


def load_checked(path: str | Path) -> tuple[Scenario, dict[str, Program]]:
    """``load_scenario`` then ``check_scenario``; raises ScenarioError."""
    scenario = load_scenario(path)
    return scenario, check_scenario(scenario)
