"""One engine cycle (infer + decide) for the driving demo's program at the demo's percept load,
against the first release's engine (a24e6ef) on its own demo, measured alternately in one run.

    .venv/bin/python bench/speed/demo_engine.py [--rounds 2] [--release ../rel-a24e6ef] [--clock
    cpu]
                                          [--split]

Each round runs the demo (scenarios/driving_demo.toml, programs/driving.tlp, 650 cycles) in
one process, as `teleo simulate` does, and times every cycle's inference and executive step:
here `Engine.infer` of the percept lists perceive() made and `Engine.decide` on them (what the
inference and executive processes call), at the release `Engine.cycle` (its infer and decide
in one call; run in the release worktree's own .venv, made by `make setup` there). By default
the time is this thread's CPU time (steady on a shared machine); `--clock wall` for wall time.
The demo's program has grown since (38 concepts and 27 skills against 19 and 15), so a third
kind runs this tree's engine on the release's program in this tree's demo world (the same
world, another program: it delivers both packages too), which sets the engines apart from the
programs. Prints, per kind, the median and mean [ms] per cycle and the percepts per cycle,
then the ratios of the medians (target: at most 0.5 ms a cycle here, issue 27). ``--split``
also times the parts of this tree's cycle (where the engine calls them; a part's time holds
the parts it calls).
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = "scenarios/driving_demo.toml"
CLOCKS = {"cpu": "thread_time", "wall": "perf_counter"}
OLD_PROGRAM = "this tree, release's program"

# Run in the release's tree and .venv: every Engine.cycle of its demo, timed. (The release
# has no separate infer/decide timing; its Engine.cycle is both.)
RELEASE = """
import json, sys, time
from agents.lang import engine as E
from tools.scenario import load_scenario
from tools.simulate import simulate
clock, out = getattr(time, sys.argv[1]), []
inner = E.Engine.cycle
def timed(self, state, percepts, *a, **k):
    t0 = clock()
    r = inner(self, state, percepts, *a, **k)
    out.append(((clock() - t0) * 1e3, len(percepts)))
    return r
E.Engine.cycle = timed
simulate(load_scenario(sys.argv[2]))
print(json.dumps(out))
"""


def release_cycles(tree: Path, clock: str) -> list[tuple[float, int]]:
    """(ms, percepts) of every engine cycle of the release's demo."""
    done = subprocess.run([str(tree / ".venv" / "bin" / "python"), "-c", RELEASE,
                           CLOCKS[clock], SCENARIO], cwd=tree, capture_output=True,
                          text=True, timeout=600)
    if done.returncode != 0:
        raise click.ClickException(f"the release's demo failed:\n{done.stderr[-2000:]}")
    return [tuple(x) for x in json.loads(done.stdout.splitlines()[-1])]


def current_cycles(clock: str, program: Path | None = None) -> list[tuple[float, int]]:
    """(ms, percepts) of every engine cycle (infer + decide) of this tree's demo, its agent
    running ``program`` if given (the release's programs/driving.tlp: same world)."""
    sys.path.insert(0, str(ROOT))
    import tools.commands.simulate as sim
    from tools.commands.sim_agents import AgentCycle, InProcessAgents
    from world.run_scenario import load_scenario

    tick, out = getattr(time, CLOCKS[clock]), []

    def agent_cycle(team, agent, snap, outcomes, memory):  # tools/commands/sim_agents.py's
        engine, state = team.engines[agent], team.states[agent]
        percepts = team.domain.perceive(snap, agent)
        t0 = tick()
        beliefs = engine.infer(percepts, memory.get("model") or ())
        decision, team.states[agent] = engine.decide(state, percepts, beliefs, outcomes)
        out.append(((tick() - t0) * 1e3, len(percepts)))
        return AgentCycle(percepts, list(outcomes), beliefs, decision, {})

    inner, InProcessAgents._agent_cycle = InProcessAgents._agent_cycle, agent_cycle
    try:
        sim.simulate(load_scenario(ROOT / SCENARIO, [f"agents.ME.program={program}"]
                                   if program else ()))
    finally:
        InProcessAgents._agent_cycle = inner
    return out


PARTS = (  # (module, object, attribute, label): timed where the engine calls them
    ("agents.lang.engine", "Engine", "infer", "infer"),
    ("agents.lang.inference.tracker", "PerceptTracker", "update",
     "  infer: what changed in the percepts"),
    ("agents.lang.inference.maintain", "Maintainer", "counting",
     "  infer: counting maintenance"),
    ("agents.lang.engine", "Engine", "decide", "decide"),
    ("agents.lang.engine", "Engine", "_index", "  decide: percepts checked and indexed"),
    ("agents.lang.execution.executive", "Executive", "_first_path",
     "  decide: skill paths"),
    ("agents.lang.execution.executive", None, "instances", "  decide: goal instances"),
    ("agents.lang.execution.circles", None, "world",
     "  decide: loop-watch digest of the world"),
)


def split(clock: str) -> dict[str, float]:
    """ms per cycle of the parts of this tree's engine cycle (PARTS), one run of the demo."""
    import importlib

    tick, spent = getattr(time, CLOCKS[clock]), dict.fromkeys([p[3] for p in PARTS], 0.0)
    undo = []
    for module, owner, name, label in PARTS:
        target = importlib.import_module(module)
        target = getattr(target, owner) if owner else target
        inner = getattr(target, name)

        def timed(*a, _inner=inner, _label=label, **k):
            t0 = tick()
            try:
                return _inner(*a, **k)
            finally:
                spent[_label] += tick() - t0

        setattr(target, name, timed)
        undo.append((target, name, inner))
    try:
        n = len(current_cycles(clock))
    finally:
        for target, name, inner in undo:
            setattr(target, name, inner)
    return {k: v * 1e3 / n for k, v in spent.items()}


@click.command()
@click.option("--split", "show_split", is_flag=True,
              help="Also time the parts of this tree's cycle (one more run).")
@click.option("--rounds", type=click.IntRange(min=1), default=2, show_default=True)
@click.option("--release", type=click.Path(exists=True, file_okay=False, path_type=Path),
              default=ROOT.parent / "rel-a24e6ef", show_default=True,
              help="A worktree of the first release with its .venv (make setup).")
@click.option("--clock", type=click.Choice(sorted(CLOCKS)), default="cpu", show_default=True)
def main(show_split: bool, rounds: int, release: Path, clock: str) -> None:
    """Print the demo's engine cycle [ms] here and at the first release."""
    old = release / "programs" / "driving.tlp"
    kinds = ("release", "this tree", OLD_PROGRAM)
    got: dict[str, list[tuple[float, int]]] = {k: [] for k in kinds}
    for k in range(rounds):
        for kind in kinds[k % 3:] + kinds[:k % 3]:
            rows = release_cycles(release, clock) if kind == "release" else \
                current_cycles(clock, old if kind == OLD_PROGRAM else None)
            got[kind] += rows
            click.echo(f"round {k + 1}: {kind:<28} median "
                       f"{statistics.median(r[0] for r in rows):.3f} ms a cycle "
                       f"({len(rows)} cycles)")
    med = {}
    for kind, rows in got.items():
        med[kind] = statistics.median(r[0] for r in rows)
        click.echo(f"{kind:<28} infer + decide: median {med[kind]:.3f} ms, mean "
                   f"{statistics.fmean(r[0] for r in rows):.3f} ms a cycle ({clock} time), "
                   f"percepts {statistics.median(r[1] for r in rows):.0f} a cycle "
                   f"(median)")
    click.echo(f"release / this tree: {med['release'] / med['this tree']:.2f}x; the engine "
               f"alone (release / this tree's engine on the release's program): "
               f"{med['release'] / med[OLD_PROGRAM]:.2f}x; target "
               f"<= 0.5 ms here: {'met' if med['this tree'] <= 0.5 else 'not met'}")
    if show_split:
        click.echo(f"this tree's cycle by part ({clock} time, ms a cycle, one run; the parts "
                   "of infer and decide are within them):")
        for label, ms in split(clock).items():
            click.echo(f"  {label:<42} {ms:.3f}")


if __name__ == "__main__":
    main()
