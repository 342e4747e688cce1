"""The demo's engine cycles replayed through this tree's engine and another tree's, alternating
in one run: the A/B measurement behind docs/benchmarks.md's "replayed" engine figures.

    .venv/bin/python bench/speed/engine_replay.py --against TREE [--rounds 8] [--reps 3]
                                                   [--cycles N]

The demo (scenarios/driving_demo.toml) runs once in this tree, as `teleo simulate` does, and
each cycle's input to the engine is kept: the percept lists perceive() made, the agent's world
model, the outcomes and the engine state. Each round then replays them through a new Engine
of this tree and of TREE (a checkout or `git archive` of another commit, e.g. main's), each in
a process of its own, ``--reps`` times: `Engine.infer` then `Engine.decide` on the same list,
timed by thread CPU time, with the garbage collector run between cycles (as `teleo simulate`
does) and never inside one. Prints each replay's median [ms a cycle] and, at the end, the
median of each tree's replays, their ratio and the median of the rounds' ratios. Nothing runs
between cycles, so the figures are the warm-cache case: the engine's own instructions, not the
memory traffic the world's step leaves it (bench/speed/demo_engine.py measures that case).
TREE must read this tree's recorded EngineState (main and a branch of it do; the first
release does not: use demo_engine.py --release for it).
"""

from __future__ import annotations

import pickle
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = "scenarios/driving_demo.toml"

# Run in a process per replay with TREE first on sys.path: the medians of ``reps`` replays.
REPLAY = """
import gc, pickle, statistics, sys, time
sys.path.insert(0, sys.argv[1])
from agents.lang import Engine, load_program
cycles = pickle.load(open(sys.argv[2], "rb"))
program = load_program(sys.argv[3])
out = []
for _ in range(int(sys.argv[4])):
    engine, ts = Engine(program), []
    gc.collect()
    gc.disable()
    for state, percepts, model, outcomes in cycles:
        t0 = time.thread_time()
        beliefs = engine.infer(percepts, model)
        engine.decide(state, percepts, beliefs, outcomes)
        ts.append(time.thread_time() - t0)
        gc.collect(0)
    gc.enable()
    out.append(statistics.median(ts) * 1e3)
print(" ".join(map(repr, out)))
"""


def record(path: Path, cycles: int | None) -> Path:
    """Run the demo in this tree, keeping every cycle's engine input in ``path``; the
    agent's program file."""
    sys.path.insert(0, str(ROOT))
    import tools.commands.simulate as sim
    from tools.commands.sim_agents import AgentCycle, InProcessAgents
    from world.run_scenario import load_scenario

    kept = []

    def agent_cycle(team, agent, snap, outcomes, memory):  # tools/commands/sim_agents.py's
        engine, state = team.engines[agent], team.states[agent]
        percepts = team.domain.perceive(snap, agent)
        model = memory.get("model") or ()
        kept.append((state, percepts, model, list(outcomes)))
        beliefs = engine.infer(percepts, model)
        decision, team.states[agent] = engine.decide(state, percepts, beliefs, outcomes)
        return AgentCycle(percepts, list(outcomes), beliefs, decision, {})

    scenario = load_scenario(ROOT / SCENARIO, [f"run.cycles={cycles}"] if cycles else ())
    inner, InProcessAgents._agent_cycle = InProcessAgents._agent_cycle, agent_cycle
    try:
        sim.simulate(scenario)
    finally:
        InProcessAgents._agent_cycle = inner
    path.write_bytes(pickle.dumps(kept))
    return scenario.agents[0].program


def replay(tree: Path, cycles: Path, program: Path, reps: int) -> list[float]:
    done = subprocess.run([sys.executable, "-c", REPLAY, str(tree), str(cycles), str(program),
                           str(reps)], capture_output=True, text=True, timeout=900)
    if done.returncode != 0:
        raise click.ClickException(f"the replay in {tree} failed:\n{done.stderr[-2000:]}")
    return [float(x) for x in done.stdout.split()]


@click.command()
@click.option("--against", "other", required=True,
              type=click.Path(exists=True, file_okay=False, path_type=Path),
              help="Another tree (checkout or git archive) to replay the same cycles in.")
@click.option("--rounds", type=click.IntRange(min=1), default=8, show_default=True)
@click.option("--reps", type=click.IntRange(min=1), default=3, show_default=True,
              help="Replays per tree and round, each through a new Engine.")
@click.option("--cycles", type=click.IntRange(min=1), default=None,
              help="Record only this many of the demo's cycles (default: all, 650).")
def main(other: Path, rounds: int, reps: int, cycles: int | None) -> None:
    """Replay the demo's engine cycles here and in another tree, alternating."""
    other = other.resolve()
    if not (other / "agents" / "lang" / "engine.py").is_file():
        raise click.BadParameter(f"{other} holds no agents/lang/engine.py (expected a teleo "
                                 f"tree)", param_hint="--against")
    with tempfile.TemporaryDirectory() as tmp:
        kept = Path(tmp) / "cycles.pickle"
        program = record(kept, cycles)
        trees = {"this tree": ROOT, "against": other}
        got: dict[str, list[float]] = {k: [] for k in trees}
        ratios = []
        for k in range(rounds):
            order = list(trees) if k % 2 == 0 else list(trees)[::-1]
            now = {name: replay(trees[name], kept, program, reps) for name in order}
            for name in order:
                got[name] += now[name]
                click.echo(f"round {k + 1}: {name:<9} " +
                           " ".join(f"{x:.3f}" for x in now[name]) + " ms a cycle")
            ratios.append(statistics.median(now["this tree"]) /
                          statistics.median(now["against"]))
    mine, theirs = (statistics.median(got[k]) for k in trees)
    click.echo(f"this tree {mine:.3f} ms, {other} {theirs:.3f} ms a cycle (median of "
               f"{rounds * reps} replays each): this / against {mine / theirs:.2f}x (rounds "
               f"{min(ratios):.2f}x to {max(ratios):.2f}x, median "
               f"{statistics.median(ratios):.2f}x)")


if __name__ == "__main__":
    main()
