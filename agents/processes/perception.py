"""The perception process of one agent: world state of t in, the agent's percepts of t out.

    python -m agents.processes.perception --run RUN --agent ME [bus flags]

Percepts are agent-centred and limited in range (seed 000, Table 3); the mapping is the
pure `perceive` of the domain the snapshot names (world/domain.py). The agent's action
outcomes of t-1 and its memory (world-model facts, SCS state), which the world state of t
carries, travel on with the percepts, and so does a program swapped in at t (WorldState.control;
agents/processes/swapping.py).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

from agents.processes.agent_setup import AgentSetup
from agents.processes.common import agent_options, run_stage, setup_logging
from bus import keys
from bus.config import BusConfig
from bus.errors import BusError, Refused
from bus.fields import MEMORY, PROGRAM
from bus.messages import Envelope, Message, Percepts, WorldState, WorldStatic
from bus.schema import FieldError, brief
from world.domain import domain_of
from world.errors import WorldError
from world.static import has_static, whole

STATIC_ASK_S = 5.0   # [s] the wait for the world's answer about its static configuration


class StaticSource:
    """The run's static world configuration (world/static.py), asked of the world once, at
    the first world state that lacks it, and kept (it is the same for the whole run)."""

    def __init__(self, run: str, process: str) -> None:
        self.run, self.process = run, process
        self.node: Any = None
        self.static: dict[str, Any] | None = None

    def bind(self, node: Any) -> None:
        """The node to ask through (run_stage calls it once the node is open)."""
        self.node = node

    def __call__(self, domain: str) -> dict[str, Any]:
        if self.static is None and self.node is not None:
            key = keys.world_static(self.run)
            try:
                reply = self.node.query(key, WorldStatic(self.node.envelope(), domain),
                                        STATIC_ASK_S)
            except BusError as exc:
                raise Refused(f"{key}: the world did not give its static part: {exc}") \
                    from None
            if isinstance(reply, WorldStatic):
                self.static = dict(reply.static)
        return self.static or {}


def with_static(state: WorldState, static: Callable[[str], dict[str, Any]] | None,
                state_key: str) -> WorldState:
    """``state`` with its snapshot whole: the run's static part, from ``static`` (a
    StaticSource), put back when it lacks it. A shared process makes it once for all its
    agents, whose perception then reads one dict (and the world checks it once: world/base.py
    `rebuild`). Refused when the static part cannot be had."""
    snap = state.snapshot
    if static is None or has_static(snap):
        return state
    try:
        return replace(state, snapshot=whole(static(str(snap.get("domain", ""))), snap))
    except WorldError as exc:
        raise Refused(f"{state_key}: the world state of cycle {state.env.cycle} from "
                      f"{brief(state.env.sender)}: {exc}") from None


def make_step(setup: AgentSetup, static: Callable[[str], dict[str, Any]] | None = None):
    """step(cycle, {state key: WorldState}) -> [(percepts key, Percepts)]. A snapshot that is
    not its world's (checked against the world's snapshot schema) is refused (bus Refused:
    the cycle waits for a good copy), naming the field. A snapshot without its static part
    gets it from ``static`` (a StaticSource) before the world perceives it."""
    run, agent, process = setup.run, setup.agent, setup.process("perception")
    state_key, out_key = keys.world_state(run), keys.percepts(run, agent)

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        state = with_static(inputs[state_key], static, state_key)
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
    setup = AgentSetup(run=run, agent=agent)
    process = setup.process("perception")
    log = setup_logging(process)
    static = StaticSource(run, process)
    run_stage(bus_config, run, process, [keys.world_state(run)], [keys.percepts(run, agent)],
              make_step(setup, static), log, bind=static.bind)


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
