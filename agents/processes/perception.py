"""The perception process of one agent: world state of t in, the agent's percepts of t out.

    python -m agents.processes.perception --run RUN --agent ME [bus flags]

Percepts are agent-centred and limited in range (seed 000, Table 3); the mapping is the
pure `perceive` of the domain the snapshot names (world/domain.py). The agent's action
outcomes of t-1 and its memory (world-model facts, SCS state), which the world state of t
carries, travel on with the percepts.
"""

from __future__ import annotations

from agents.processes.common import agent_options, run_stage, setup_logging
from bus import keys
from bus.config import BusConfig
from bus.messages import Envelope, Message, Percepts


def make_step(run: str, agent: str, process: str):
    """step(cycle, {state key: WorldState}) -> [(percepts key, Percepts)]."""
    from world.domain import domain_of

    state_key, out_key = keys.world_state(run), keys.percepts(run, agent)

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        state = inputs[state_key]
        percepts = tuple(list(p) for p in domain_of(state.snapshot).perceive(state.snapshot,
                                                                             agent))
        outcomes = tuple(state.outcomes.get(agent, ()))
        memory = state.memory.get(agent) or {}
        return [(out_key, Percepts(Envelope.now(run, cycle, process), agent, percepts,
                                   outcomes, memory if isinstance(memory, dict) else {}))]

    return step


@agent_options(with_program=False)
def main(run: str, agent: str, bus_config: BusConfig) -> None:
    """Perception of one agent."""
    process = f"{agent}.perception"
    log = setup_logging(process)
    run_stage(bus_config, run, process, [keys.world_state(run)], [keys.percepts(run, agent)],
              make_step(run, agent, process), log)


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
