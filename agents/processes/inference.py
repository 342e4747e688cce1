"""The inference process of one agent: percepts of t in, beliefs of t out.

    python -m agents.processes.inference --run RUN --agent ME --program FILE [bus flags]

Beliefs are every concept instance that holds, inferred bottom-up to fixpoint from the
percepts (seed 000, Inference and Execution Mechanisms). Sorted, so the bytes on the bus are
the same for the same percepts.
"""

from __future__ import annotations

import click

from agents.processes.common import run_stage, setup_logging
from bus import keys
from bus.config import BusConfig, bus_options
from bus.messages import Beliefs, Envelope, Message


def make_step(run: str, agent: str, process: str, program_path: str):
    """step(cycle, {percepts key: Percepts}) -> [(beliefs key, Beliefs)]."""
    from agents.lang import Engine, load_program

    engine = Engine(load_program(program_path))
    in_key, out_key = keys.percepts(run, agent), keys.beliefs(run, agent)

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        beliefs = engine.infer(inputs[in_key].percepts)
        lists = tuple(sorted((b.to_list() for b in beliefs), key=repr))
        return [(out_key, Beliefs(Envelope.now(run, cycle, process), agent, lists))]

    return step


@click.command()
@click.option("--run", required=True, help="Run id.")
@click.option("--agent", required=True, help="Agent id, e.g. ME.")
@click.option("--program", required=True, type=click.Path(exists=True, dir_okay=False),
              help="The agent's teleoreactive program (.tlp).")
@bus_options
def main(run: str, agent: str, program: str, bus_config: BusConfig) -> None:
    """Belief inference of one agent."""
    process = f"{agent}.inference"
    log = setup_logging(process)
    step = make_step(run, agent, process, program)
    run_stage(bus_config, run, process, [keys.percepts(run, agent)], [keys.beliefs(run, agent)],
              step, log)


if __name__ == "__main__":
    main()
