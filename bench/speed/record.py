"""What recording a run costs: the driving demo launched in lockstep with its run record
(record.mcap, the default) and without (--no-record), interleaved, plus the record's size.

    .venv/bin/python bench/speed/record.py [--pairs 5] [--scenario scenarios/driving_demo.toml]

Prints each launch's cycles per second (the world's own timing, world-final.json), the median
of each kind, their ratio (recorded / not recorded), and the record's bytes per cycle.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import click
from mcap.reader import make_reader

ROOT = Path(__file__).resolve().parents[2]


def launch(scenario: Path, record: bool) -> tuple[float, int, int, float]:
    """One launch: (cycles per second, cycles, record bytes or 0, the recorder thread's CPU
    time per cycle [ms] or 0)."""
    with tempfile.TemporaryDirectory() as tmp:
        teleo = str(Path(sys.executable).parent / "teleo")
        args = [teleo, "launch", str(scenario), "--summary", f"{tmp}/s.json"]
        done = subprocess.run(args + ([] if record else ["--no-record"]), cwd=ROOT,
                              env={**os.environ, "TELEO_RUN_DIR": tmp}, capture_output=True,
                              text=True, timeout=900)
        if done.returncode != 0:
            raise click.ClickException(f"launch failed:\n{done.stdout}\n{done.stderr}")
        summary = json.loads(Path(f"{tmp}/s.json").read_text())
        mcap = Path(summary["trace"]).with_name("record.mcap")
        if not record:
            return summary["cycles_per_s"], summary["cycles"], 0, 0.0
        with mcap.open("rb") as f:  # metadata written by tools/records/recorder.py
            meta = {m.name: m.metadata for m in make_reader(f).iter_metadata()}
        cpu_ms = float(meta["teleo.recorder"]["cpu_ms"])
        return (summary["cycles_per_s"], summary["cycles"], mcap.stat().st_size,
                cpu_ms / summary["cycles"])


@click.command()
@click.option("--pairs", type=click.IntRange(min=1), default=5, show_default=True)
@click.option("--scenario", type=click.Path(exists=True, path_type=Path),
              default=ROOT / "scenarios" / "driving_demo.toml", show_default=True)
def main(pairs: int, scenario: Path) -> None:
    with_rec: list[float] = []
    without: list[float] = []
    sizes: list[float] = []
    cpu: list[float] = []
    for k in range(pairs):
        for record in (k % 2 == 0, k % 2 == 1):  # alternate which goes first
            rate, cycles, size, cpu_ms = launch(scenario, record)
            (with_rec if record else without).append(rate)
            if record:
                sizes.append(size / cycles)
                cpu.append(cpu_ms)
            click.echo(f"pair {k + 1}: {'recorded    ' if record else 'not recorded'} "
                       f"{rate:8.1f} cycles/s ({1e3 / rate:.2f} ms a cycle)" + (
                           f", {size / cycles:.0f} B/cycle, recorder CPU {cpu_ms:.3f} ms/cycle"
                           if record else ""))
    a, b = statistics.median(with_rec), statistics.median(without)
    click.echo(f"median cycles/s: recorded {a:.1f}, not recorded {b:.1f}, ratio {a / b:.3f}")
    c = statistics.median(cpu)
    click.echo(f"recorder thread CPU: {c:.3f} ms per cycle = {c * b / 1e3:.1%} of the "
               f"unrecorded cycle time ({1e3 / b:.2f} ms)")
    click.echo(f"record size: {statistics.median(sizes):.0f} bytes per cycle (zstd chunks)")
    click.echo(f"load average at the end: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
