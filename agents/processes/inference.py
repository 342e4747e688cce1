"""The inference process of one agent: percepts of t in, beliefs of t out.

    python -m agents.processes.inference --run RUN --agent ME --program FILE [bus flags]

Beliefs are every concept instance that holds, inferred bottom-up to fixpoint from the
percepts (seed 000, Inference and Execution Mechanisms). Sorted, so the bytes on the bus are
the same for the same percepts.
"""

from __future__ import annotations

from agents.processes.common import agent_options, run_stage, setup_logging
from bus import keys
from bus.config import BusConfig
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


@agent_options(with_program=True)
def main(run: str, agent: str, program: str, bus_config: BusConfig) -> None:
    """Belief inference of one agent."""
    process = f"{agent}.inference"
    log = setup_logging(process)
    step = make_step(run, agent, process, program)
    run_stage(bus_config, run, process, [keys.percepts(run, agent)], [keys.beliefs(run, agent)],
              step, log)


if __name__ == "__main__":
    main()
