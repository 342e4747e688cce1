"""End-to-end lockstep cycle rate of the full stack with N cars that really drive and deliver:
router, world, goal entry and, per agent, perception, inference and executive as separate
processes on zenoh (bench/speed/fleet.py: one agent-independent program, each car its own package).

    .venv/bin/python bench/speed/cycle.py [--cycles 600] [--agents 1,2,4,8] [--shared 0,all,auto]
                                    [--record]

For each agent count it writes the fleet scenario, runs `teleo launch --cycles N` (without
the run record unless --record) and reads the summary and the world's timing totals
(world-final.json): cycles per second, the mean cycle time [ms], each stage's mean compute
time per cycle [ms] with its share of the cycle (the rest is the bus: zenoh, msgpack, and the
processes' wake-ups), the resident memory of the agents' processes per agent [MiB]
(sampled every 0.2 s; the peak), and each process's own CPU time a cycle from cycle 50 on
(/proc, as bench/speed/cycle_cpu.py: its step and its decode, checks, encode and zenoh
threads), summed by role, with the cores that kept busy: on a machine shared with other work
the cycle rate follows the load, the CPU a cycle hardly. It checks that every agent acted
(sent actions in most cycles) and delivered its package (its goal achieved, its deliveries
counter 1); a count that fails the check is reported and the bench exits 1. Delivery takes
about 215 cycles.

--shared: the launch layouts to compare, as `teleo launch --agents-per-process K` values: 0 a
process per stage (3 per agent), 1 a process per agent, `all` every agent in one process
(agents/processes/shared.py), `auto` the agents spread over the machine's CPUs
(tools/launching/run_plan.py `per_core`). The first layout is the baseline of the "x" column.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
import threading
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "bench" / "speed"))

from cycle_cpu import _cpu_s, _cycles, _role  # noqa: E402
from fleet import write_fleet  # noqa: E402

STAGES = ("world", "goals", "perception", "inference", "executive")
PAGE_KIB = os.sysconf("SC_PAGE_SIZE") / 1024


def _tree(pid: int) -> list[int]:
    """``pid`` and all its descendants (Linux /proc)."""
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        out.append(p)
        try:
            tasks = list(Path(f"/proc/{p}/task").glob("*"))
        except OSError:  # the process ended meanwhile
            continue
        for task in tasks:
            try:
                todo += [int(c) for c in (task / "children").read_text().split()]
            except OSError:
                pass
    return out


def _agent_rss_kib(pid: int) -> float:
    """Resident memory [KiB] of the processes under ``pid`` that serve an agent."""
    total = 0.0
    for p in _tree(pid):
        try:
            if b"--agent" not in Path(f"/proc/{p}/cmdline").read_bytes():
                continue
            total += int(Path(f"/proc/{p}/statm").read_text().split()[1]) * PAGE_KIB
        except (OSError, IndexError, ValueError):
            pass
    return total


class LaunchFailed(Exception):
    """A launch of the bench that ended with an error (the line saying why)."""


def run_once(scenario: Path, cycles: int, record: bool, per_process: int | str) -> dict:
    """One launch; returns its summary, the world's timing totals, the agents' peak RSS and
    the launch's line on how the agents' stages share processes ("" for a process each)."""
    tmp = scenario.parent
    env = {**os.environ, "TELEO_RUN_DIR": str(tmp)}
    teleo = str(Path(sys.executable).parent / "teleo")
    cmd = [teleo, "launch", str(scenario), "--cycles", str(cycles),
           "--summary", f"{tmp}/s.json", "--agents-per-process", str(per_process),
           *(() if record else ("--no-record",))]
    proc = subprocess.Popen(cmd, cwd=ROOT, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    peak = [0.0]
    cpu: list[tuple[int, dict[str, float]]] = []  # (cycles done, CPU [s] by role), sampled
    done = threading.Event()

    def sample() -> None:
        while not done.wait(0.2):
            peak[0] = max(peak[0], _agent_rss_kib(proc.pid))
            cpu.append((_cycles(tmp), _cpu_by_role(proc.pid)))

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    out, err = proc.communicate(timeout=1800)
    done.set()
    sampler.join()
    if proc.returncode != 0:
        why = [x for x in (out + err).splitlines() if "failed:" in x or x.startswith("Error")]
        raise LaunchFailed(f"launch failed ({proc.returncode}): "
                           f"{why[0].strip() if why else err.strip()[-300:]}")
    summary = json.loads(Path(f"{tmp}/s.json").read_text())
    run_dir = Path(summary["trace"]).parent
    final = json.loads((run_dir / "world-final.json").read_text())
    acted = _cycles_with_actions(run_dir / "trace.jsonl")
    layout = next((x for x in out.splitlines()
                   if x.startswith("each agent's") or " agents in " in x), "")
    return {**summary, "timing_ms": final["timing_ms"], "rss_kib": peak[0], "acted": acted,
            "layout": layout, "cpu_ms": _cpu_per_cycle(cpu)}


def _cpu_by_role(pid: int) -> dict[str, float]:
    """CPU time [s] (user + system) of the launch's processes so far, summed by role (world
    "process", "goals", "shared" for the agents' processes, "perception", ...)."""
    out: dict[str, float] = {}
    for p in _tree(pid):
        role, c = _role(p), _cpu_s(p)
        if role is not None and c is not None:
            out[role] = out.get(role, 0.0) + c
    return out


def _cpu_per_cycle(samples: list[tuple[int, dict[str, float]]]) -> dict[str, float]:
    """CPU [ms] a cycle of each role, from the first sample at or past cycle 50 (start-up
    left out: the agents' processes load their programs then) to the last one while the
    world still ran; empty for a run too short to tell."""
    steady = [(n, c) for n, c in samples if n >= 50 and "process" in c]
    if len(steady) < 2 or steady[-1][0] <= steady[0][0]:
        return {}
    (n0, c0), (n1, c1) = steady[0], steady[-1]
    return {role: (c1[role] - c0.get(role, 0.0)) * 1e3 / (n1 - n0) for role in c1}


def _cycles_with_actions(trace: Path) -> dict[str, int]:
    """Per agent, the cycles whose trace line applied at least one action of it."""
    counts: dict[str, int] = {}
    for line in trace.read_text().splitlines():
        for agent, acts in json.loads(line)["actions"].items():
            counts[agent] = counts.get(agent, 0) + bool(acts)
    return counts


def failures(agents: int, result: dict) -> list[str]:
    """What the run did not do: an agent that did not act or did not deliver."""
    out = []
    achieved = {g["agent"] for g in result["goals"] if g["status"] == "achieved"}
    for k in range(1, agents + 1):
        a = f"A{k}"
        if result["acted"].get(a, 0) == 0:   # a car that delivered and parked acts no more
            out.append(f"{a} never acted in {result['cycles']} cycles")
        delivered = result["counters"].get(a, {}).get("deliveries", 0)
        if a not in achieved or delivered < 1:
            out.append(f"{a} did not deliver P{k} (deliveries {delivered})")
    return out


def stage_means(result: dict) -> dict[str, float]:
    """Mean compute time per cycle of each stage kind [ms], summed over agents."""
    timing, cycles = result["timing_ms"], max(result["cycles"], 1)
    means = {"world": timing["world"] / cycles}
    for process, total in timing["stages"].items():
        kind = process.split(".")[-1]
        means[kind] = means.get(kind, 0.0) + total / cycles
    return means


def report(agents: int, layout: str, result: dict, base: float) -> None:
    cycles = max(result["cycles"], 1)
    cycle_ms = (result["timing_ms"]["cycle"] + result["timing_ms"]["world"]) / cycles
    delivered = sum(c.get("deliveries", 0) for c in result["counters"].values())
    click.echo(f"{agents} agent(s), {layout}: {result['cycles_per_s']:.1f} cycles/s "
               f"(x {result['cycles_per_s'] / base:.2f}), "
               f"{cycle_ms:.2f} ms per cycle, late stages "
               f"{sum(result['late_stages'].values())}, deliveries {delivered}/{agents}, "
               f"agents' memory {result['rss_kib'] / 1024 / agents:.1f} MiB per agent")
    means = stage_means(result)
    for kind in STAGES:
        ms = means.get(kind, 0.0)
        note = f" (sum over {agents} agents)" if (
            agents > 1 and kind in ("perception", "inference", "executive")) else ""
        click.echo(f"  {kind:<11} {ms:7.3f} ms  {100 * ms / cycle_ms:5.1f} %{note}")
    rest = cycle_ms - sum(means.values())
    if rest > 0:
        click.echo(f"  {'bus+waits':<11} {rest:7.3f} ms  {100 * rest / cycle_ms:5.1f} %")
    cpu = result["cpu_ms"]
    if cpu:   # each process's own CPU: its step and its decode, checks, encode, zenoh
        names = {"process": "world", "shared": "agents' processes",
                 "teleo launch": "launcher"}
        parts = ", ".join(f"{names.get(r, r)} {ms:.2f}" for r, ms in sorted(
            cpu.items(), key=lambda x: -x[1]))
        click.echo(f"  CPU a cycle from cycle 50: {sum(cpu.values()):.2f} ms ({parts}); "
                   f"{sum(cpu.values()) / cycle_ms:.2f} cores busy")


def _counts(text: str, name: str, allow_all: bool) -> list:
    """A comma-separated list of non-negative counts (and "all" where allowed)."""
    out = []
    for x in text.split(","):
        if allow_all and x in ("all", "auto"):
            out.append(x)
        elif x.isdigit() and (allow_all or 1 <= int(x) <= 32):
            out.append(int(x))
        else:
            what = "a count, all or auto" if allow_all else "a count 1..32"
            raise click.BadParameter(f"{x!r} is not {what}", param_hint=f"--{name}")
    return out


@click.command()
@click.option("--cycles", default=600, show_default=True,
              help="Cycles per launch (delivery takes about 215).")
@click.option("--agents", default="1,2,4,8", show_default=True, callback=lambda c, p, v:
              _counts(v, p.name, allow_all=False),
              help="Agent counts, comma-separated (1..32).")
@click.option("--shared", default="0,all,auto", show_default=True, callback=lambda c, p, v:
              _counts(v, p.name, allow_all=True),
              help="Layouts: --agents-per-process values (0, 1, ..., all, auto), "
                   "comma-separated.")
@click.option("--record", is_flag=True, help="Keep the run record (record.mcap) on.")
def main(cycles: int, agents: list, shared: list, record: bool) -> None:
    """Print end-to-end lockstep cycle rates of N delivering cars and each stage's share."""
    load = os.getloadavg()[0]
    click.echo(f"fleet of cars on programs/driving.tlp bound through self, {cycles} cycles, "
               f"lockstep, {os.cpu_count()} CPUs, load average {load:.1f}")
    bad = []
    for n in agents:
        base = 0.0
        for k in dict.fromkeys(n if x == "all" else x for x in shared):
            layout = {0: "a process per stage", 1: "a process per agent", "auto": "auto"}.get(
                k, f"{k} agents per process")
            with tempfile.TemporaryDirectory() as tmp:
                try:
                    result = run_once(write_fleet(Path(tmp), n, cycles), cycles, record, k)
                except LaunchFailed as exc:   # reported, and the other layouts still run
                    click.echo(f"{n} agent(s), {layout}: {exc}")
                    bad.append(f"{n} agents, {layout}: {exc}")
                    continue
            base = base or result["cycles_per_s"]
            if k == "auto":  # the launch says how many processes it chose
                got = re.search(r"(\d+) process", result["layout"])
                n_proc = got.group(1) if got else "?"
                layout = f"auto ({n_proc} agent process{'' if n_proc == '1' else 'es'})"
            report(n, layout, result, base)
            bad += [f"{n} agents, {layout}: {f}" for f in failures(n, result)]
    for line in bad:
        click.echo(f"FAILED {line}")
    sys.exit(1 if bad else 0)

if __name__ == "__main__":
    main()
