"""The driving demo against the first release (a24e6ef), measured alternately in one run:
the launch `make demo` runs (lockstep, a process per stage), this tree's without the run
record (--no-record) and with it, and the release's (which had no run record).

    git -C . worktree add ../rel-a24e6ef a24e6ef && make -C ../rel-a24e6ef setup   # once
    .venv/bin/python bench/speed/release.py [--pairs 3] [--release ../rel-a24e6ef]

Each round launches the three, in an order that rotates from round to round (the machine is
shared: a neighbour's load hits all three alike), and times each whole process. Prints each
launch's cycles per second (the summary's: cycles over the world's elapsed time), the wall
time of the whole `teleo launch` (start-up and shutdown included) and the CPU time all its
processes took per cycle (start-up included: on a loaded machine the steadiest of the three,
as it does not count the time others' processes held the cores), the medians, and the
ratios of the medians: this tree without the record over the release (target >= 2x, issue
27) and with the record over without (target >= 0.9x, issue 36).
"""

from __future__ import annotations

import json
import os
import resource
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = "scenarios/driving_demo.toml"
KINDS = ("release", "no record", "record")


def _children_cpu_s() -> float:
    """CPU time [s] (user + system) of the ended child processes waited for so far (a launch
    waits for its own: the router, the world, the stages)."""
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def launch(tree: Path, extra: tuple[str, ...]) -> tuple[float, float, int, float]:
    """One demo launch in ``tree`` (its own .venv): (cycles/s, whole-process wall s, cycles,
    CPU s of all its processes)."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [str(tree / ".venv" / "bin" / "teleo"), "launch", SCENARIO,
               "--summary", f"{tmp}/s.json", *extra]
        t0, cpu0 = time.perf_counter(), _children_cpu_s()
        done = subprocess.run(cmd, cwd=tree, env={**os.environ, "TELEO_RUN_DIR": tmp},
                              capture_output=True, text=True, timeout=900)
        wall, cpu = time.perf_counter() - t0, _children_cpu_s() - cpu0
        if done.returncode != 0:
            raise click.ClickException(f"launch in {tree} failed:\n{done.stdout}\n{done.stderr}")
        summary = json.loads(Path(f"{tmp}/s.json").read_text())
        return summary["cycles_per_s"], wall, summary["cycles"], cpu


@click.command()
@click.option("--pairs", type=click.IntRange(min=1), default=3, show_default=True,
              help="Rounds of the three launches.")
@click.option("--release", type=click.Path(exists=True, file_okay=False, path_type=Path),
              default=ROOT.parent / "rel-a24e6ef", show_default=True,
              help="A worktree of the first release with its .venv (make setup).")
def main(pairs: int, release: Path) -> None:
    """Print the demo's cycles/s here (record off and on) and at the first release."""
    trees = {"release": (release, ()), "no record": (ROOT, ("--no-record",)),
             "record": (ROOT, ())}
    rates: dict[str, list[float]] = {k: [] for k in KINDS}
    walls: dict[str, list[float]] = {k: [] for k in KINDS}
    cpus: dict[str, list[float]] = {k: [] for k in KINDS}
    click.echo(f"driving demo, lockstep, a process per stage; {os.cpu_count()} CPUs, "
               f"load average {os.getloadavg()[0]:.1f}")
    for k in range(pairs):
        order = KINDS[k % 3:] + KINDS[:k % 3]
        for kind in order:
            rate, wall, cycles, cpu = launch(*trees[kind])
            rates[kind].append(rate)
            walls[kind].append(wall)
            cpus[kind].append(cpu * 1e3 / cycles)
            click.echo(f"round {k + 1}: {kind:<9} {rate:7.1f} cycles/s "
                       f"({1e3 / rate:.2f} ms a cycle), whole process {wall:5.2f} s "
                       f"for {cycles} cycles, CPU {cpu * 1e3 / cycles:.2f} ms a cycle")
    med = {k: statistics.median(v) for k, v in rates.items()}
    wmed = {k: statistics.median(v) for k, v in walls.items()}
    cmed = {k: statistics.median(v) for k, v in cpus.items()}
    for kind in KINDS:
        click.echo(f"median {kind:<9} {med[kind]:7.1f} cycles/s, whole process "
                   f"{wmed[kind]:5.2f} s, CPU {cmed[kind]:.2f} ms a cycle")
    click.echo(f"this tree (no record) / release: {med['no record'] / med['release']:.2f}x "
               f"cycles/s (target 2x), {wmed['release'] / wmed['no record']:.2f}x whole process")
    click.echo(f"record on / off: {med['record'] / med['no record']:.2f}x cycles/s "
               f"(target 0.9x)")
    click.echo(f"load average at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
