"""Warnings about a goal that is accepted: a goal with variables means every instance
(docs/language.md, "Goals with variables"), and when the world's objects give it an instance
that no skill or concept can make true, such as ``(on D D)`` among ``(on D ?x)``'s, the user
is told so, and pointed to the conjunction form ``(and ...)`` for "some instance". Judged on
the scenario's world as it starts (the objects a run begins with). ``teleo check`` and the
goal-entry process's replies to ``teleo goal post`` both use it."""

from __future__ import annotations

from collections.abc import Callable

from agents.lang import Engine, GoalError, LangError, as_percepts, load_program
from agents.lang.core.store import PerceptIndex, store_of
from agents.lang.reading.goals import parse_goal
from agents.lang.registry import instances_warning, never_true
from world.domain import get_domain
from world.errors import WorldError
from world.run_scenario import Scenario

Warner = Callable[[str, str], str]
"""warn(agent, goal text) -> "" or one line saying which instances nothing can make true."""


def engine_warner(scenario: Scenario, programs: dict | None = None,
                  eager: bool = False) -> Warner:
    """warn(agent, goal) for ``scenario``'s agents, from each agent's percepts of the world the
    scenario starts with; ``programs``: agent -> loaded Program (loaded here when None). A goal
    that does not read, or a world that cannot be made, gives no warning (the validator and
    the scenario check say what is wrong with those). The world is made once, for every
    agent, at the first warning, or here when ``eager`` (the goal-entry process: before it
    announces itself, so that no cycle waits for a world to be made)."""
    engines = {a.id: Engine((programs or {}).get(a.id) or load_program(str(a.program)))
               for a in scenario.agents}
    seen: dict[str, tuple | None] = {}

    def look() -> None:
        try:
            domain = get_domain(scenario.domain)
            snap = domain.create(scenario.world_table, scenario.run.seed,
                                 list(scenario.agent_ids)).snapshot_dict()
        except (WorldError, LangError):   # a world that cannot be made warns of nothing
            seen.update(dict.fromkeys(engines))   # (the scenario check says why)
            return
        for agent, engine in engines.items():
            try:
                pidx = PerceptIndex(as_percepts(domain.perceive(snap, agent)))
                seen[agent] = (pidx, store_of(engine.infer(pidx)))
            except (WorldError, LangError):
                seen[agent] = None

    def situation(agent: str) -> tuple | None:
        if not seen:
            look()
        return seen.get(agent)

    if eager:
        look()

    def warn(agent: str, goal: str) -> str:
        engine = engines.get(agent)
        now = situation(agent) if engine is not None else None
        if now is None:
            return ""
        try:
            parsed = parse_goal(goal, engine.program)
        except GoalError:
            return ""
        return instances_warning(parsed, never_true(engine.program, parsed, *now))

    return warn
