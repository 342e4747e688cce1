"""`teleo launch --agents-per-process K` (or `auto`: the agents spread over the CPUs): several
agents' stages in one process (agents/processes/shared.py) give the same lockstep run as a
process per stage: the same trace, every agent acting, fewer processes."""

from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

import pytest
from e2e_helpers import ROOT, two_cars

from tools.launching.cpus import usable_cores
from tools.records.run_record import RunRecord


def test_two_agents_in_one_process_run_exactly_as_in_six(teleo, tmp_path):
    scenario = two_cars(tmp_path)
    apart = teleo("launch", scenario, "--no-record", "--json", timeout=300)
    shared = teleo("launch", scenario, "--json", "--agents-per-process", "2", timeout=300)
    spread = teleo("launch", scenario, "--no-record", "--json", "--agents-per-process", "auto",
                   timeout=300)
    for done in (apart, shared, spread):
        assert done.returncode == 0, done.stderr
    counts = [int(re.search(r"run \S+: (\d+) processes", r.stderr).group(1))
              for r in (apart, shared, spread)]
    # goals, world, 3 stages x 2 agents | goals, world, agents1 | on two or more CPUs,
    # goals, world, agents1, agents2: a process for each agent
    cpus = usable_cores()   # what the launch spread its agents over
    assert counts == [8, 3, 4 if cpus >= 2 else 3]
    assert "agents1" in shared.stderr
    assert "2 agents in 1 process of up to 2 agents each\n" in shared.stderr
    assert (f"each agent's three stages in one process: 2 processes (--agents-per-process "
            f"auto: {cpus} CPUs)" if cpus >= 2 else "in 1 process") in spread.stderr
    traces = [open(json.loads(r.stdout)["trace"]).read() for r in (apart, shared, spread)]
    assert traces[0] == traces[1] == traces[2]
    lines = [json.loads(line) for line in traces[1].splitlines()]
    assert len(lines) == 25
    for agent in ("A1", "A2"):  # both agents decided: their gas or brake was applied
        assert any(line["actions"][agent] for line in lines), agent
    summary = json.loads(shared.stdout)
    assert summary["late_stages"] == {} and summary["dead_stages"] == {}
    # issue 36: each stage's stats carried in its output, as separate stages carry them;
    # an agent's actions hold its whole pipeline's, the goal entry's included
    record = RunRecord(Path(summary["record"]))
    for agent in ("A1", "A2"):
        stages = [f"{agent}.{s}" for s in ("perception", "inference", "executive")]
        for kind, held in (("percepts", stages[:1]), ("beliefs", stages[:2]),
                           ("actions", ["goals", *stages])):
            carried = [sorted(r["stats"]) for _, r in record.kinds_of((kind,), agent)]
            assert carried == [sorted(held)] * len(carried) and len(carried) >= 25, kind


def test_agents_per_process_is_refused_for_a_secured_run(teleo, tmp_path):
    done = teleo("launch", two_cars(tmp_path), "--secure", "--agents-per-process", "1",
                 timeout=120)
    assert done.returncode == 1
    assert "--agents-per-process: only for a whole open run on one host" in done.stderr
    assert "Traceback" not in done.stderr


@pytest.mark.parametrize("value", ["many", "-1", "2.5"])
def test_agents_per_process_must_be_a_count_or_auto(teleo, tmp_path, value):
    done = teleo("launch", two_cars(tmp_path), "--agents-per-process", value, timeout=60)
    assert done.returncode == 2
    assert (f"Invalid value for '--agents-per-process': '{value}' is not a count of agents "
            f"(0, 1, 2, ...) or auto") in done.stderr
    assert "Traceback" not in done.stderr


def _fleet(tmp_path, agents: int, cycles: int) -> str:
    """bench/speed/fleet.py's scenario: ``agents`` cars on one program, each its own package."""
    spec = importlib.util.spec_from_file_location("fleet", ROOT / "bench" / "speed" / "fleet.py")
    fleet = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fleet)
    return str(fleet.write_fleet(tmp_path, agents, cycles))


def test_a_launch_too_big_for_a_peer_mesh_runs_its_processes_as_clients(teleo, tmp_path):
    scenario = _fleet(tmp_path, 11, 12)   # 35 processes: more than a mesh of peers holds
    clients = teleo("launch", scenario, "--no-record", "--json", timeout=600)
    peers = teleo("launch", scenario, "--no-record", "--json", "--agents-per-process", "11",
                  timeout=300)
    assert clients.returncode == 0, clients.stderr[-3000:]
    assert peers.returncode == 0, peers.stderr[-3000:]
    assert re.search(r"run \S+: 35 processes and a router at \S+, clients of the router,",
                     clients.stderr)
    assert re.search(r"run \S+: 3 processes and a router at \S+, logs in", peers.stderr)
    traces = [open(json.loads(r.stdout)["trace"]).read() for r in (clients, peers)]
    assert traces[0] == traces[1]
    lines = [json.loads(line) for line in traces[0].splitlines()]
    assert len(lines) == 12
    assert all(any(line["actions"][f"A{k}"] for line in lines) for k in range(1, 12))
