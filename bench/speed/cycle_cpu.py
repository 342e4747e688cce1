"""Where a demo launch's cycle goes: each process's own CPU time per cycle against the cycle's
wall time, measured from outside (Linux /proc), without a profiler in the processes.

    .venv/bin/python bench/speed/cycle_cpu.py [--runs 3] [--record] [--agents-per-process 0]

Launches the driving demo (lockstep, --no-record unless --record) and samples every 0.1 s the
CPU time (user + system, /proc/PID/stat) of each process of the launch and the cycles done so
far (the lines of the run's trace.jsonl). The figures are the differences between the first
sample at or past cycle 50 (start-up and the first cycles left out) and the last one before
the world ends, per cycle [ms]: a process's CPU time is its own work (decode, checks, its
stage's step, encode, puts, zenoh's threads in it) and the rest of the cycle it waits. Prints
each process's ms per cycle, beside the part of it its step took (the compute times the world
totals in world-final.json, over the whole run), their sum, the wall time per cycle and the
share of the two cores the launch kept busy, as the median over the runs.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
TICK = os.sysconf("SC_CLK_TCK")
ROLES = ("bus.router", "world.process", "goals", "perception", "inference", "executive",
         "shared", "teleo launch")


def _children(pid: int) -> list[int]:
    """``pid``'s descendants (Linux /proc)."""
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        for task in Path(f"/proc/{p}/task").glob("*"):
            try:
                kids = [int(c) for c in (task / "children").read_text().split()]
            except OSError:
                continue
            out += kids
            todo += kids
    return out


def _role(pid: int) -> str | None:
    try:
        cmd = Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode()
    except OSError:
        return None
    return next((r.split(".")[-1] if "." in r else r for r in ROLES if r in cmd), None)


def _cpu_s(pid: int) -> float | None:
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / TICK  # utime, stime [ticks]


def _cycles(run_dir: Path) -> int:
    traces = list(run_dir.glob("runs/*/trace.jsonl"))
    try:
        return traces[0].read_bytes().count(b"\n") if traces else 0
    except OSError:
        return 0


def one_run(record: bool, per_process: str) -> dict[str, float]:
    """One launch: ms of CPU per cycle of each role, plus "wall" (ms per cycle)."""
    with tempfile.TemporaryDirectory() as tmp:
        cmd = [str(Path(sys.executable).parent / "teleo"), "launch",
               "scenarios/driving_demo.toml", "--agents-per-process", per_process,
               *(() if record else ("--no-record",))]
        proc = subprocess.Popen(cmd, cwd=ROOT, env={**os.environ, "TELEO_RUN_DIR": tmp},
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        first: tuple | None = None
        last: tuple | None = None
        while proc.poll() is None:
            n = _cycles(Path(tmp))
            pids = [proc.pid, *_children(proc.pid)]
            cpu: dict[str, float] = {}
            for p in pids:
                role, c = _role(p), _cpu_s(p)
                if role is not None and c is not None:
                    cpu[role] = cpu.get(role, 0.0) + c
            sample = (n, time.perf_counter(), cpu)
            if n >= 50 and first is None:
                first = sample
            if first is not None and "process" in cpu and n > first[0]:
                last = sample
            time.sleep(0.1)
        if first is None or last is None or proc.returncode != 0:
            raise click.ClickException(f"launch failed or too short (rc {proc.returncode})")
        final = json.loads(next(Path(tmp).glob("runs/*/world-final.json")).read_text())
    cycles = last[0] - first[0]
    out = {role: (last[2].get(role, 0.0) - first[2].get(role, 0.0)) * 1e3 / cycles
           for role in last[2]}
    out["wall"] = (last[1] - first[1]) * 1e3 / cycles
    timing, done = final["timing_ms"], max(last[0], 1)   # the whole run's step times
    out["step:process"] = timing["world"] / done
    for name, total in timing["stages"].items():
        out[f"step:{name.split('.')[-1]}"] = total / done
    return out


@click.command()
@click.option("--runs", type=click.IntRange(min=1), default=3, show_default=True)
@click.option("--record", is_flag=True, help="Keep the run record on.")
@click.option("--agents-per-process", "per_process", default="0", show_default=True)
def main(runs: int, record: bool, per_process: str) -> None:
    """Print each process's CPU ms per cycle of the demo against the cycle's wall time."""
    got = [one_run(record, per_process) for _ in range(runs)]
    click.echo(f"driving demo, lockstep, --agents-per-process {per_process}, "
               f"{'record on' if record else 'no record'}, {runs} run(s), load average "
               f"{os.getloadavg()[0]:.1f}; CPU ms per cycle from cycle 50 on (median):")
    roles = sorted({r for g in got for r in g if not r.startswith("step:")} - {"wall"})
    total = 0.0
    for role in roles:
        ms = statistics.median(g.get(role, 0.0) for g in got)
        total += ms
        step = [g[f"step:{role}"] for g in got if f"step:{role}" in g]
        click.echo(f"  {role:<12} {ms:6.3f} ms" + (
            f", of which its step {statistics.median(step):.3f} ms (the world's timing)"
            if step else ""))
    wall = statistics.median(g["wall"] for g in got)
    click.echo(f"  {'all':<12} {total:6.3f} ms of CPU a cycle; the cycle takes {wall:.3f} ms "
               f"({1e3 / wall:.0f} cycles/s): {total / wall:.2f} cores busy of "
               f"{os.cpu_count()}")


if __name__ == "__main__":
    main()
