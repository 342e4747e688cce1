"""Perception benchmark: one agent's perception per cycle for the driving demo's world, from the
world state as the bus delivers it (decoded, without its static part) to the Percepts message
encoded for the bus, against the earlier path in the same run.

    .venv/bin/python bench/speed/perception.py [--cycles 650] [--repeat 5]

The demo (scenarios/driving_demo.toml) is run in one process (`teleo simulate`'s path) to
collect its world states; then each is encoded and decoded as the world process sends it and
perception's step is timed over all of them, alternating the two paths, best of ``--repeat``:

baseline   the path before issue 36: the snapshot rebuilt as objects (WorldSnapshot.from_dict,
           a frozen dataclass per car, pedestrian and package) and perceived from them by
           world/driving/perception.py as it was at commit BASE (read with `git show`), the
           memory and program checked, the Percepts encoded
current    the perception process's step as it is (agents/processes/perception.py), its
           Percepts encoded (bus/codec.py)

Both paths must give the same rows for every cycle (checked first; a difference stops it).
Prints ms per cycle for each and their ratio.
"""

from __future__ import annotations

import argparse
import gc
import subprocess
import sys
import time
import types
from pathlib import Path

# this file is bench/speed/perception.py: keep its folder off the path so `world` is the package
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).parent.resolve()]

from agents.processes.agent_setup import AgentSetup  # noqa: E402
from agents.processes.perception import make_step  # noqa: E402
from bus import keys  # noqa: E402
from bus.codec import decode, encode  # noqa: E402
from bus.fields import MEMORY, PROGRAM  # noqa: E402
from bus.messages import Envelope, Percepts, WorldState  # noqa: E402
from tools.commands.simulate import simulate  # noqa: E402
from world.driving.snapshot import WorldSnapshot  # noqa: E402
from world.run_scenario import load_scenario  # noqa: E402
from world.static import split, whole  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
RUN, AGENT = "bench", "ME"
BASE = "89d6333"   # the last commit before perception read snapshot dicts (issue 36)


def module_at(commit: str, path: str) -> types.ModuleType:
    """The module of ``path`` as it was at ``commit`` (its imports are today's)."""
    text = subprocess.run(["git", "show", f"{commit}:{path}"], cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout
    module = types.ModuleType(f"before_{Path(path).stem}")
    exec(compile(text, f"{commit}:{path}", "exec"), module.__dict__)  # noqa: S102
    return module


def world_states(cycles: int) -> tuple[dict, list[WorldState]]:
    """(the static part, the demo's world states of ``cycles`` cycles as perception decodes
    them)."""
    scenario = load_scenario(ROOT / "scenarios" / "driving_demo.toml")
    run = simulate(scenario, cycles=cycles, keep_every=1)
    static, states = None, []
    for cycle, snap in enumerate(run.snapshots):
        told, moving = split(snap)
        static = static or told
        data = encode(WorldState(Envelope.now(RUN, cycle, "world"), moving, {AGENT: []}, []))
        states.append(decode(keys.world_state(RUN), data))
    return static or {}, states


def baseline(static: dict) -> object:
    """The earlier path: an object per row, perceived by the earlier module."""
    perceive = module_at(BASE, "world/driving/perception.py").perceive

    def step(cycle: int, state: WorldState) -> bytes:
        snap = whole(static, state.snapshot)
        rows = tuple(list(p) for p in perceive(WorldSnapshot.from_dict(snap), AGENT))
        memory = state.memory.get(AGENT) or {}
        MEMORY.check(memory)
        PROGRAM.check({})
        return encode(Percepts(Envelope.now(RUN, cycle, "p"), AGENT, rows, (), memory, {}))
    return step


def current(static: dict) -> object:
    step = make_step(AgentSetup(run=RUN, agent=AGENT), lambda domain: static)
    key = keys.world_state(RUN)

    def run(cycle: int, state: WorldState) -> bytes:
        return encode(step(cycle, {key: state})[0][1])
    return run


def timed(step, states: list[WorldState]) -> float:
    """ms per cycle over all states, the collector off as in a stage process."""
    gc.disable()
    try:
        t0 = time.perf_counter()
        for cycle, state in enumerate(states):
            step(cycle, state)
        return (time.perf_counter() - t0) / len(states) * 1e3
    finally:
        gc.enable()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cycles", type=int, default=650)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    if args.cycles < 1 or args.repeat < 1:
        parser.error(f"expected --cycles and --repeat >= 1, got {args.cycles}, {args.repeat}")
    static, states = world_states(args.cycles)
    paths = {"baseline": baseline(static), "current": current(static)}
    key = keys.percepts(RUN, AGENT)
    for cycle, state in enumerate(states):
        got = {name: decode(key, step(cycle, state)).percepts for name, step in paths.items()}
        if got["baseline"] != got["current"]:
            sys.exit(f"cycle {cycle}: the two paths perceive differently")
    best = {name: float("inf") for name in paths}
    for _ in range(args.repeat):
        for name, step in paths.items():
            best[name] = min(best[name], timed(step, states))
    print(f"perception, driving demo, agent {AGENT}, {len(states)} cycles, best of {args.repeat}")
    for name, ms in best.items():
        print(f"{name:>9} {ms:8.3f} ms/cycle")
    print(f"{'ratio':>9} {best['current'] / best['baseline']:8.2f}x (current / baseline)")


if __name__ == "__main__":
    main()
