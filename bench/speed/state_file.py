"""The executive's state file: its cost per cycle when every cycle is written (the policy before
issue 36) against writing only the cycles whose decision changed the state, in the same run.

    .venv/bin/python bench/speed/state_file.py [--repeat 5] [--scenario FILE]

The scenario (the driving demo by default) runs in one process (`teleo simulate`'s path),
keeping the agent's engine state after every cycle; then each policy saves that sequence of
states to a file of its own (agents/processes/persist.py StateFile, with an empty intention
and no actions: the state is what differs). Prints ms per cycle for each, their ratio, and how
many cycles changed the state.
"""

from __future__ import annotations

import argparse
import gc
import sys
import tempfile
import time
from pathlib import Path

sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).parent.resolve()]

import logging  # noqa: E402

from agents.processes.persist import Saved, StateFile  # noqa: E402
from tools.commands.simulate import simulate  # noqa: E402
from world.run_scenario import load_scenario  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LOG = logging.getLogger("bench")


def states_of(scenario: Path) -> list:
    """The first agent's engine state after every cycle of ``scenario``."""
    sc = load_scenario(scenario)
    agent, out = sc.agent_ids[0], []
    simulate(sc, until=lambda states: out.append(states[agent]) and False)
    return out


def timed(states: list, folder: Path, only_changed: bool) -> tuple[float, int]:
    """(ms per cycle, cycles written) saving ``states`` under one policy."""
    file = StateFile(folder / f"state-{only_changed}.json", LOG)
    written = 0
    gc.disable()
    try:
        t0 = time.perf_counter()
        for cycle, state in enumerate(states):
            if not only_changed or file.changed(state):
                file.save(Saved(cycle, state, {}, []))
                written += 1
        return (time.perf_counter() - t0) / len(states) * 1e3, written
    finally:
        gc.enable()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--scenario", type=Path, default=ROOT / "scenarios" / "driving_demo.toml")
    args = parser.parse_args()
    if args.repeat < 1:
        parser.error(f"expected --repeat >= 1, got {args.repeat}")
    states = states_of(args.scenario)
    best = {False: float("inf"), True: float("inf")}
    written = {}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.repeat):
            for policy in best:
                ms, written[policy] = timed(states, Path(tmp), policy)
                best[policy] = min(best[policy], ms)
    print(f"executive state file, {args.scenario.name}, {len(states)} cycles, best of "
          f"{args.repeat}")
    print(f"{'every cycle':>14} {best[False]:8.4f} ms/cycle  ({written[False]} written)")
    print(f"{'when changed':>14} {best[True]:8.4f} ms/cycle  ({written[True]} written)")
    print(f"{'ratio':>14} {best[True] / best[False]:8.2f}x")


if __name__ == "__main__":
    main()
