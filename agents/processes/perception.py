"""The perception process of one agent: world state of t in, the agent's percepts of t out.

    python -m agents.processes.perception --run RUN --agent ME [bus flags]

Percepts are agent-centred and limited in range (seed 000, Table 3); the mapping is the
pure `perceive` of the domain the snapshot names (world/domain.py). The agent's action
outcomes of t-1 and its memory (world-model facts, SCS state), which the world state of t
carries, travel on with the percepts, and so does a program swapped in at t (WorldState.control;
agents/processes/swapping.py).
"""

from __future__ import annotations

from agents.processes.common import agent_options, run_stage, setup_logging
from bus import keys
from bus.config import BusConfig
from bus.errors import Refused
from bus.fields import MEMORY, PROGRAM
from bus.messages import Envelope, Message, Percepts
from bus.schema import FieldError, brief


def make_step(run: str, agent: str, process: str):
    """step(cycle, {state key: WorldState}) -> [(percepts key, Percepts)]. A snapshot that is
    not its world's (checked against the world's snapshot schema) is refused (bus Refused:
    the cycle waits for a good copy), naming the field."""
    from world.domain import domain_of
    from world.errors import WorldError

    state_key, out_key = keys.world_state(run), keys.percepts(run, agent)

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        state = inputs[state_key]
        try:
            seen = domain_of(state.snapshot).perceive(state.snapshot, agent)
        except WorldError as exc:
            raise Refused(f"{state_key}: the world state of cycle {cycle} from "
                          f"{brief(state.env.sender)}: {exc}") from None
        percepts = tuple(list(p) for p in seen)
        outcomes = tuple(state.outcomes.get(agent, ()))
        memory = state.memory.get(agent) or {}
        program = (state.control.get("programs") or {}).get(agent) or {}
        try:
            MEMORY.check(memory)   # what it forwards (the codec checked only its shape)
        except FieldError as exc:
            raise Refused(f"{state_key}: the world state of cycle {cycle}: memory."
                          f"{exc.within(agent)}") from None
        try:
            PROGRAM.check(program)   # a program swapped in at this cycle (teleo program load)
        except FieldError as exc:
            raise Refused(f"{state_key}: the world state of cycle {cycle}: control.programs."
                          f"{exc.within(agent)}") from None
        return [(out_key, Percepts(Envelope.now(run, cycle, process), agent, percepts,
                                   outcomes, memory, program))]

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
