"""The inference process of one agent: percepts of t in, beliefs of t out.

    python -m agents.processes.inference --run RUN --agent ME --program FILE [bus flags]

Beliefs are every concept instance that holds, inferred bottom-up to fixpoint from the
percepts and the agent's world model (facts its SCS bodies asserted, which come back in the
percepts message's memory; seed 000, Inference and Execution Mechanisms; seed 002). Sorted,
so the bytes on the bus are the same for the same percepts.
"""

from __future__ import annotations

import logging
from operator import itemgetter
from typing import Any

import click

from agents.lang import Engine, LangError, SharedRows
from agents.processes.agent_setup import AgentSetup
from agents.processes.common import agent_options, run_stage, setup_logging
from agents.processes.per_object import PerObject
from agents.processes.swapping import keep, kept, note, read_program, said
from bus import keys
from bus.config import BusConfig
from bus.errors import Refused
from bus.messages import Beliefs, Envelope, Message
from bus.schema import brief


def make_step(setup: AgentSetup, log: logging.Logger | None = None):
    """step(cycle, {percepts key: Percepts}) -> [(beliefs key, Beliefs)]. Percepts the engine
    cannot read are refused (bus Refused), naming the percept; a malformed world model is
    logged and left out. A program that comes with the percepts is swapped in first
    (agents/processes/swapping.py), and the beliefs of the cycle say so."""
    run, agent, process = setup.run, setup.agent, setup.process("inference")
    log = log or logging.getLogger(process)
    engine = Engine(kept(setup.swapped, setup.program, log))
    in_key, out_key = keys.percepts(run, agent), keys.beliefs(run, agent)

    rows = BeliefRows()

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        nonlocal engine
        seen = inputs[in_key]
        swap: dict = {}
        if seen.program:
            program, why = read_program(seen.program)
            if program is not None:
                engine = Engine(program)
                keep(setup.swapped, seen.program, cycle, log)
            swap = note(seen.program, why)
            said(process, cycle, swap, log)
        percepts = SharedRows(seen.percepts)  # rows seen last cycle are the same lists
        try:
            beliefs = engine.infer(percepts, seen.memory.get("model") or ())
        except LangError as exc:   # a malformed model: logged, inferred without it
            try:
                beliefs = engine.infer(percepts)
            except LangError as bad:   # the percepts themselves: refused, naming the percept
                raise Refused(f"{in_key}: the percepts of cycle {cycle} from "
                              f"{brief(seen.env.sender)}: {bad}") from None
            log.warning("cycle %d: world model dropped: %s", cycle, exc)
        return [(out_key, Beliefs(Envelope.now(run, cycle, process), agent,
                                  rows.of(beliefs), swap))]

    return step


class BeliefRows:
    """A belief set as sorted neutral lists; a belief held last cycle keeps its list (the
    codec then sends its bytes again without packing, and receivers get the same list), and
    the same set as last cycle gives the same tuple."""

    def __init__(self) -> None:
        self.last: object = None
        self.rows: tuple = ()
        self.lists = PerObject(_keyed)

    def of(self, beliefs: frozenset) -> tuple:
        if beliefs is not self.last:
            self.last = beliefs
            self.rows = tuple(r for _, r in sorted(self.lists.of(beliefs), key=_KEY))
        return self.rows


def _keyed(belief: Any) -> tuple[str, list]:
    """(the sort key, the neutral list) of a belief."""
    row = belief.to_list()
    return repr(row), row


_KEY = itemgetter(0)


@click.option("--swapped", type=click.Path(dir_okay=False),
              help="Keep a program swapped in here, and start from the one it holds.")
@agent_options(with_program=True)
def main(run: str, agent: str, program: str, bus_config: BusConfig,
         swapped: str | None) -> None:
    """Belief inference of one agent."""
    setup = AgentSetup(run=run, agent=agent, program=program, swapped=swapped)
    process = setup.process("inference")
    log = setup_logging(process)
    run_stage(bus_config, run, process, [keys.percepts(run, agent)], [keys.beliefs(run, agent)],
              make_step(setup, log), log)


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
