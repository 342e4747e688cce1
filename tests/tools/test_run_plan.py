"""What `teleo launch` starts and how its processes meet (tools/launching/run_plan.py): a few
processes are peers, many are clients of the router (a full mesh of 50 peers ran at 4 cycles/s on
two cores, one of 98 never started), and start-up gets more time the more processes there are."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from tools.launching.run_plan import (
    PEER_MESH_LIMIT,
    Plan,
    per_core,
    process_specs,
    processes_started,
    select,
    start_timeout,
    with_bus_mode,
)
from world.run_scenario import scenario_from_dict

PROGRAM = Path(__file__).resolve().parents[1] / "e2e" / "fixtures" / "hold_speed.tlp"


def plan_of(agents: int, per_process: int = 0) -> Plan:
    doc = {"agents": [{"id": f"A{k}", "program": str(PROGRAM)} for k in range(1, agents + 1)]}
    scenario = scenario_from_dict(doc, Path("fleet.toml"))
    plan = Plan(scenario, "r", Path("/tmp/r"), 10, 1, "lockstep", select(scenario, None),
                agents_per_process=per_process)   # no endpoint: the router is not up yet
    return replace(with_bus_mode(plan), endpoint="tcp/127.0.0.1:7447")


def bus_args(plan: Plan) -> dict[str, tuple[str, str]]:
    """Per process: its --mode and --listen flags."""
    out = {}
    for spec in process_specs(plan):
        argv = list(spec.argv)
        out[spec.name] = (argv[argv.index("--mode") + 1], argv[argv.index("--listen") + 1])
    return out


@pytest.mark.parametrize("agents, per_process, started, clients", [
    (1, 0, 5, False), (9, 0, 29, False), (10, 0, 32, True), (16, 0, 50, True),
    (16, 1, 18, False), (16, 16, 3, False), (32, 1, 34, True), (32, 8, 6, False)])
def test_more_processes_than_a_peer_mesh_holds_are_clients_of_the_router(
        agents, per_process, started, clients):
    plan = plan_of(agents, per_process)
    assert processes_started(plan) == started == len(process_specs(plan))
    assert plan.client is clients is (started > PEER_MESH_LIMIT)
    modes = set(bus_args(plan).values())
    # a client listens nowhere: the router is the only thing listening
    assert modes == ({("client", "")} if clients else {("peer", "tcp/127.0.0.1:0")})


def test_a_plan_already_of_clients_stays_so():
    plan = replace(plan_of(1), client=True)
    assert with_bus_mode(plan) is plan


def test_start_up_gets_two_seconds_a_process_beyond_a_minute():
    idle = (0.5, 2)
    assert [start_timeout(n, idle) for n in (1, 5, 30, 31, 50, 98)] == [60, 60, 60, 62, 100,
                                                                         196]
    assert start_timeout(5, (40.0, 2)) == 60 * 8      # load 40 on 2 CPUs (issue 31)
    assert start_timeout(5, (6.0, 2)) == 180


@pytest.mark.parametrize("agents, cores, per_process, agent_processes", [
    (1, 2, 1, 1), (2, 2, 1, 2), (3, 2, 2, 2), (4, 2, 2, 2), (8, 2, 4, 2), (32, 2, 16, 2),
    (8, 16, 1, 8), (32, 16, 2, 16), (33, 16, 3, 11), (5, 1, 5, 1), (3, 0, 3, 1)])
def test_auto_spreads_the_agents_over_the_cores(agents, cores, per_process, agent_processes):
    """--agents-per-process auto: no more agent processes than cores, each agent in one."""
    assert per_core(agents, cores) == per_process
    plan = plan_of(agents, per_process)
    names = [s.name for s in process_specs(plan)]
    assert names == ["goals", *(f"agents{k}" for k in range(1, agent_processes + 1)), "world"]
