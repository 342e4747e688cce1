"""End-to-end lockstep cycle rate of the full stack: router, world, goal entry and, per
agent, perception, inference and executive as separate processes on zenoh.

    .venv/bin/python bench/cycle.py [--cycles 300] [--agents 1,4] [--program FILE]

For each agent count it writes a scenario, runs `teleo launch --cycles N` in lockstep and
reads the world's timing totals (world-final.json): cycles per second, the mean cycle time
[ms], and each stage's mean compute time per cycle [ms] with its share of the cycle. The
rest of the cycle is the bus (zenoh, msgpack) and the processes' wake-ups. The program is
programs/driving.tlp when it exists, else the end-to-end tests' hold-speed program.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[1]
STAGES = ("world", "goals", "perception", "inference", "executive")


def scenario_text(agents: int, program: Path, cycles: int) -> str:
    """A city with `agents` cars (default start places), pedestrians and traffic."""
    lines = ['[run]', 'name = "bench"', 'mode = "lockstep"', f"cycles = {cycles}", "seed = 1",
             "", "[world]", "grid = [4, 4]", "pedestrians = 12", "traffic = 4", ""]
    for k in range(agents):
        lines += ["[[agents]]", f'id = "A{k + 1}"', f'program = "{program}"', ""]
    return "\n".join(lines)


def run_once(agents: int, program: Path, cycles: int) -> dict:
    """One launch; returns its summary plus the world's timing totals."""
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "bench.toml"
        path.write_text(scenario_text(agents, program, cycles))
        env = {**os.environ, "TELEO_RUN_DIR": tmp}
        teleo = str(Path(sys.executable).parent / "teleo")
        done = subprocess.run([teleo, "launch", str(path), "--summary", f"{tmp}/s.json"],
                              cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
        if done.returncode != 0:
            raise click.ClickException(f"launch failed:\n{done.stdout}\n{done.stderr}")
        summary = json.loads(Path(f"{tmp}/s.json").read_text())
        final = json.loads((Path(summary["trace"]).parent / "world-final.json").read_text())
    return {**summary, "timing_ms": final["timing_ms"]}


def stage_means(result: dict) -> dict[str, float]:
    """Mean compute time per cycle of each stage kind [ms], summed over agents."""
    timing, cycles = result["timing_ms"], max(result["cycles"], 1)
    means = {"world": timing["world"] / cycles}
    for process, total in timing["stages"].items():
        kind = process.split(".")[-1]
        means[kind] = means.get(kind, 0.0) + total / cycles
    return means


def report(agents: int, result: dict) -> None:
    cycles = max(result["cycles"], 1)
    cycle_ms = (result["timing_ms"]["cycle"] + result["timing_ms"]["world"]) / cycles
    click.echo(f"{agents} agent(s): {result['cycles_per_s']:.1f} cycles/s, "
               f"{cycle_ms:.2f} ms per cycle, late stages {sum(result['late_stages'].values())}")
    means = stage_means(result)
    for kind in STAGES:
        ms = means.get(kind, 0.0)
        note = f" (sum of {agents} agents' processes, which run in parallel)" if (
            agents > 1 and kind in ("perception", "inference", "executive")) else ""
        click.echo(f"  {kind:<11} {ms:7.3f} ms  {100 * ms / cycle_ms:5.1f} %{note}")
    if agents == 1:
        rest = cycle_ms - sum(means.values())
        click.echo(f"  {'bus+waits':<11} {rest:7.3f} ms  {100 * rest / cycle_ms:5.1f} %")


@click.command()
@click.option("--cycles", default=300, show_default=True)
@click.option("--agents", default="1,4", show_default=True, help="Agent counts, comma-separated.")
@click.option("--program", type=click.Path(exists=True, dir_okay=False), default=None)
def main(cycles: int, agents: str, program: str | None) -> None:
    """Print end-to-end lockstep cycle rates and each stage's share of the cycle."""
    driving = ROOT / "programs" / "driving.tlp"
    fallback = ROOT / "tests" / "e2e" / "fixtures" / "hold_speed.tlp"
    prog = Path(program) if program else (driving if driving.exists() else fallback)
    click.echo(f"program {prog.relative_to(ROOT) if prog.is_relative_to(ROOT) else prog}, "
               f"{cycles} cycles, lockstep, {os.cpu_count()} CPUs")
    for n in (int(x) for x in agents.split(",")):
        report(n, run_once(n, prog.resolve(), cycles))


if __name__ == "__main__":
    main()
