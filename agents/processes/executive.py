"""The executive process of one agent: percepts, beliefs and goal list of t in; actions and
intention of t out.

    python -m agents.processes.executive --run RUN --agent ME --program FILE [bus flags]

Each cycle it brings the engine's user goals in line with the goal list the goal-entry
process published for t (posted, cancelled, reprioritised goals), then takes one executive
step: the first unsatisfied goal of the prioritised list gets a skill path, the previous
path preferred (seed 000, Adding Goal Priorities). The intention is Decision.to_dict(): the
goal list with statuses, the skill path with bindings, the actions and why. The engine state
(the path) lives here; the goals live in the goal-entry process, so a restart loses none.
"""

from __future__ import annotations

import logging
from typing import Any

from agents.processes.common import agent_options, run_stage, setup_logging
from bus import keys
from bus.config import BusConfig
from bus.messages import Actions, Envelope, Intention, Message


class Executive:
    """The engine state of one agent plus the user goals it was last given."""

    def __init__(self, engine: Any, log: logging.Logger) -> None:
        self.engine = engine
        self.log = log
        self.state = engine.initial_state()
        self.user: dict[str, tuple[str, int]] = {}  # goal id -> (goal text, priority)
        self.refused: set[str] = set()

    def sync_goals(self, goal_list: tuple[dict[str, Any], ...]) -> None:
        """Add new goals, drop withdrawn ones, move reprioritised ones (in list order)."""
        from agents.lang import GoalError

        wanted = {g["id"]: (g["goal"], int(g["priority"])) for g in goal_list}
        for goal_id in [i for i in self.user if i not in wanted]:
            self.state = self.engine.remove_goal(self.state, goal_id)
            del self.user[goal_id]
        for goal_id, (text, priority) in wanted.items():
            known = self.user.get(goal_id)
            try:
                if known is None and goal_id not in self.refused:
                    self.state = self.engine.add_goal(self.state, text, priority=priority,
                                                      goal_id=goal_id)
                elif known is not None and known[1] != priority:
                    self.state = self.engine.set_priority(self.state, goal_id, priority)
                else:
                    continue
            except GoalError as exc:
                self.log.warning("goal %s %s refused by the engine: %s", goal_id, text, exc)
                self.refused.add(goal_id)
                continue
            self.user[goal_id] = (text, priority)

    def decide(self, percepts: tuple, belief_lists: tuple, outcomes: tuple = ()) -> Any:
        """One executive step; returns the engine's Decision. A malformed outcome is logged
        and left out, never a crash (the world's outcomes are checked by the engine)."""
        from agents.lang import Belief, LangError
        from agents.lang.outcomes import as_outcomes

        beliefs = frozenset(Belief.from_list(b) for b in belief_lists)
        good = []
        for o in outcomes:
            try:
                good += as_outcomes([o])
            except LangError as exc:
                self.log.warning("outcome dropped: %s", exc)
        decision, self.state = self.engine.decide(self.state, percepts, beliefs, good)
        return decision


def make_step(run: str, agent: str, process: str, program_path: str, log: logging.Logger):
    """step(cycle, {percepts, beliefs, goal list}) -> [(intention, ...), (actions, ...)]."""
    from agents.lang import Engine, load_program

    executive = Executive(Engine(load_program(program_path)), log)
    p_key, b_key, g_key = (keys.percepts(run, agent), keys.beliefs(run, agent),
                           keys.goal_list(run, agent))

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        executive.sync_goals(inputs[g_key].goals)
        seen = inputs[p_key]
        decision = executive.decide(seen.percepts, inputs[b_key].beliefs, seen.outcomes)
        actions = tuple(a.to_list() for a in decision.actions)
        env = Envelope.now(run, cycle, process)
        return [(keys.intention(run, agent), Intention(env, agent, decision.to_dict())),
                (keys.actions(run, agent), Actions(env, agent, actions))]

    return step


@agent_options(with_program=True)
def main(run: str, agent: str, program: str, bus_config: BusConfig) -> None:
    """Prioritised executive of one agent."""
    process = f"{agent}.executive"
    log = setup_logging(process)
    inputs = [keys.percepts(run, agent), keys.beliefs(run, agent), keys.goal_list(run, agent)]
    run_stage(bus_config, run, process, inputs, [keys.actions(run, agent)],
              make_step(run, agent, process, program, log), log)


if __name__ == "__main__":
    main()
