"""A pass-through agent stage: the smallest real process on the bus, used by the tests and
bench/speed/bus.py, and an example of a process module (subscribe, call the core, publish).

    python -m bus.passthrough --run r1 --agent A --stage inference [--log FILE] [--die-at N]

perception: world state -> Percepts (the snapshot's "percepts"[agent], else one percept
naming the cycle); inference: Percepts -> Beliefs (copied); executive: Beliefs -> Actions
`[["*pass", cycle, n_beliefs]]`. `--log` appends each computed cycle number, one per line;
`--die-at N` SIGKILLs the process itself when the inputs of cycle N arrive.
"""

from __future__ import annotations

import os
import signal
import threading

import click

from bus import keys
from bus.config import BusConfig, bus_options
from bus.messages import Actions, Beliefs, Message, Percepts, WorldState
from bus.node import Node, open_node
from bus.stage import Stage, stop_on_signals

STAGES = ("perception", "inference", "executive")


def percepts_200() -> list[list]:
    """The pass-through benches' load (bench/speed/bus.py, bench/speed/bus_hops.py): 200 percepts
    shaped like the driving domain's (seed 000, Table 3)."""
    rows: list[list] = [["self", "ME", "speed", 20.0, "limit", 25, "segment", "S2724"]]
    for i in range(199):
        rows.append(["lane-line", f"L{i}", "dist", 1.5 + i * 0.01, "angle", 2.0 * i,
                     "segment", f"S{2700 + i}", "color", "yellow"])
    return rows


def wiring(run: str, agent: str, stage: str) -> tuple[str, str]:
    """(input key, output key) of a pass-through stage."""
    chain = [keys.world_state(run), keys.percepts(run, agent), keys.beliefs(run, agent),
             keys.actions(run, agent)]
    i = STAGES.index(stage)
    return chain[i], chain[i + 1]


def make_step(node: Node, agent: str, stage: str, log_path: str | None, die_at: int | None):
    """The step function of a pass-through stage."""
    in_key, out_key = wiring(node.run, agent, stage)

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        if die_at is not None and cycle == die_at:
            os.kill(os.getpid(), signal.SIGKILL)
        if log_path:
            fd = os.open(log_path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
            try:
                os.write(fd, f"{cycle}\n".encode())
            finally:
                os.close(fd)
        msg = inputs[in_key]
        env = node.envelope(cycle)
        if isinstance(msg, WorldState):
            rows = msg.snapshot.get("percepts", {}).get(agent) or [["cycle", str(cycle)]]
            return [(out_key, Percepts(env, agent, tuple(rows)))]
        if isinstance(msg, Percepts):
            return [(out_key, Beliefs(env, agent, msg.percepts))]
        assert isinstance(msg, Beliefs)
        return [(out_key, Actions(env, agent, (["*pass", cycle, len(msg.beliefs)],)))]

    return step


def run_stage(cfg: BusConfig, run: str, agent: str, stage: str, log_path: str | None = None,
              die_at: int | None = None, stop: threading.Event | None = None) -> None:
    """Run one pass-through stage until `stop` is set (default: until SIGINT/SIGTERM)."""
    if stop is None:
        stop = stop_on_signals(child=True)
    process = f"{agent}.{stage}"
    with open_node(cfg, run, process) as node:
        in_key, out_key = wiring(run, agent, stage)
        Stage(node, process, [in_key], make_step(node, agent, stage, log_path, die_at),
              outputs=[out_key]).run(stop)


@click.command()
@click.option("--run", "run_id", required=True)
@click.option("--agent", required=True)
@click.option("--stage", type=click.Choice(STAGES), required=True)
@click.option("--log", "log_path", default=None, help="Append each computed cycle here.")
@click.option("--die-at", type=int, default=None, help="SIGKILL itself at this cycle.")
@bus_options
def main(run_id: str, agent: str, stage: str, log_path: str | None, die_at: int | None,
         bus_config: BusConfig) -> None:
    run_stage(bus_config, run_id, agent, stage, log_path, die_at)


if __name__ == "__main__":
    from bus.lifeline import run_then_exit

    run_then_exit(main)
