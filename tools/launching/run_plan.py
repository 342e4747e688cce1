"""What one `teleo launch` starts, and with which bus settings (tools/commands/launch.py runs it).

A scenario's processes are the goal-entry process, each agent's perception, inference and
executive, and the world; a launch also starts the router unless it joins another launch's
run (`--join ENDPOINT --run RUN`). `--only` picks a subset by name: `world`, `goals`, an
agent id (its three stages) or a full process name (`ME.executive`), so that the processes of
one run can be spread over several hosts (docs/faults.md, "Across hosts").

Bus settings: on one host, in the open, every process is a zenoh peer that meets the others
at the router and then talks to them directly (the fastest for a few processes). A secured run
(`--secure`), a router listening beyond loopback, or a joining launch makes every process a
client of the router: the router is then the only thing listening, it authenticates each
process with its own user and password over TLS and applies the run's access-control list
(bus/security.py). A launch of more than PEER_MESH_LIMIT processes makes them clients too:
peers connect to every other peer, and beyond about 30 processes the connections' upkeep
slows a run more than the router's extra hop, and at 98 processes keeps it from starting at
all (docs/benchmarks.md, "Bus", "Peers or clients").
"""

from __future__ import annotations

import json
import secrets
from dataclasses import dataclass, replace
from pathlib import Path

from agents.processes.agent_setup import AgentSetup
from bus.config import BusConfig, Mode
from bus.load import scaled
from tools.launching.run_secrets import RunSecrets, host_of
from tools.launching.supervisor import ProcSpec, module_argv
from world.run_scenario import AGENT_STAGES, AgentSpec, Scenario

_MODULES = {"perception": "agents.processes.perception",
            "inference": "agents.processes.inference",
            "executive": "agents.processes.executive"}
_LOOPBACK = ("127.0.0.1", "localhost", "::1")
RESUME_ARGS = ("--resume",)


class PlanError(ValueError):
    """A launch that cannot be planned (an unknown name in --only, a missing secret)."""


@dataclass(frozen=True)
class Plan:
    """Everything needed to start the processes of one launch."""

    scenario: Scenario
    run: str
    run_dir: Path
    cycles: int
    seed: int
    mode: str
    local: tuple[str, ...]          # process names started here (router excluded)
    endpoint: str = ""              # the router's, once known (or the one joined)
    listen: str = "tcp/127.0.0.1:0"  # where the router listens (port 0: any free port)
    secrets: RunSecrets | None = None
    client: bool = False            # processes are clients of the router
    joined: bool = False
    ready_timeout: float = 60.0     # [s] the world waits for every stage
    learned: str | None = None      # skills learned in an earlier run, for every executive
    record: bool = True             # write the run record (record.mcap; the world's host only)
    agents_per_process: int = 0     # > 0: that many agents' stages share a process (shared.py)

    @property
    def runs_world(self) -> bool:
        return "world" in self.local


PEER_MESH_LIMIT = 30  # processes: a launch of more makes them clients of the router
START_S = 60.0             # [s] the least time a launch's processes get to announce themselves
START_S_PER_PROCESS = 2.0  # [s] more per process: their start-ups share the machine's cores


def start_timeout(processes: int, load: tuple[float, int] | None = None) -> float:
    """How long [s] a launch waits for ``processes`` processes started on its host to
    announce themselves: each imports zenoh, numpy and its stage's code, and on two cores
    98 processes (32 agents, a process per stage) need more than a minute to do so; on a
    busy machine, more again (bus/load.py: stretched by the load per CPU; `load`: (load
    average, CPUs), else the machine's now)."""
    return scaled(max(START_S, START_S_PER_PROCESS * processes), load=load)


def all_processes(scenario: Scenario) -> list[str]:
    """Every process of a scenario in start order (the world last: it is the clock)."""
    names = ["goals"]
    for agent in scenario.agents:
        names += [f"{agent.id}.{stage}" for stage in AGENT_STAGES]
    return names + ["world"]


def select(scenario: Scenario, only: str | None) -> tuple[str, ...]:
    """The processes named by --only (comma-separated), in start order; all without it."""
    every = all_processes(scenario)
    if not only:
        return tuple(every)
    wanted: set[str] = set()
    for name in (n.strip() for n in only.split(",") if n.strip()):
        if name in every:
            wanted.add(name)
        elif name in scenario.agent_ids:
            wanted |= {f"{name}.{stage}" for stage in AGENT_STAGES}
        else:
            raise PlanError(f"--only: unknown process or agent {name!r}; expected world, goals, "
                            f"an agent ({', '.join(scenario.agent_ids)}) or one of {every}")
    return tuple(n for n in every if n in wanted)


def uses_clients(secure: bool, joined: bool, listen: str) -> bool:
    """Whether the processes must be clients of the router (module doc)."""
    host = host_of(listen)
    return secure or joined or host not in _LOOPBACK


def processes_started(plan: Plan) -> int:
    """How many processes the plan starts on this host, the router left out (the agents'
    stages share processes with --agents-per-process K: one per K agents). Counted, not
    taken from `process_specs`: the bus mode is chosen before the router and its endpoint,
    which every spec's command line names, exist."""
    if plan.agents_per_process <= 0:
        return len(plan.local)
    agents = len(plan.scenario.agents)
    return len(plan.local) - 3 * agents + agent_processes(agents, plan.agents_per_process)


def agent_processes(agents: int, per_process: int) -> int:
    """How many processes ``agents`` agents' stages take, ``per_process`` to a process."""
    return -(-agents // per_process)


def per_core(agents: int, cores: int) -> int:
    """``--agents-per-process auto``: K that spreads ``agents`` over ``cores`` processes, as
    evenly as consecutive groups allow (1 agent or 2 on two cores: a process each; 8: two of
    4). In lockstep the world steps while the agents wait and the agents work while the world
    waits, so the agents' processes can have every core; on two cores 8 cars ran 1.3 times as
    many cycles a second as in one process, and 4 cars 1.3 times (bench/speed/cycle.py)."""
    return max(1, -(-agents // max(1, cores)))


def with_bus_mode(plan: Plan) -> Plan:
    """The plan with its processes made clients of the router when they are too many to
    mesh as peers (module doc)."""
    if plan.client or processes_started(plan) <= PEER_MESH_LIMIT:
        return plan
    return replace(plan, client=True)


def bus_config(plan: Plan, user: str) -> BusConfig:
    """The bus settings of one process of the plan (`user`: its process name)."""
    if not plan.client:
        return BusConfig(connect=(plan.endpoint,))
    cred = str(plan.secrets.credentials(user)) if plan.secrets else ""
    return BusConfig(mode=Mode.CLIENT, connect=(plan.endpoint,), listen=(), credentials=cred)


def process_specs(plan: Plan) -> list[ProcSpec]:
    """The command of every local process of the plan, in start order."""
    from tools.records import summary

    sc = plan.scenario
    path = str(sc.path.resolve())
    specs = []
    shared = _shared_specs(plan) if plan.agents_per_process > 0 else {}
    for name in plan.local:
        agent, _, stage = name.rpartition(".")
        if agent in shared:  # its stages run in its group's process, listed at the first
            if shared[agent] is not None and stage == "perception":
                specs.append(shared[agent])
            continue
        common = ["--run", plan.run, *bus_config(plan, name).to_args()]
        changed = [arg for text in sc.overrides for arg in ("--set", text)]
        if name == "goals":
            specs.append(ProcSpec(name, module_argv(
                "agents.processes.goals", *common, "--scenario", path, *changed,
                "--store", str(plan.run_dir / "goals.json")), sc.run.goals_respawn))
        elif name == "world":
            specs.append(ProcSpec(name, module_argv(
                "world.process", *common, "--scenario", path, *changed,
                "--cycles", str(plan.cycles),
                "--seed", str(plan.seed), "--run-mode", plan.mode, "--out", str(plan.run_dir),
                "--ready-timeout", str(plan.ready_timeout),
                *(["--recorded"] if plan.record else [])), 3, restart_args=RESUME_ARGS))
        else:
            agent, _, stage = name.rpartition(".")
            spec = sc.agent(agent)
            extra = [] if stage == "perception" else [
                "--program", str(spec.program.resolve()),
                "--swapped", str(summary.swapped_file(plan.run_dir, agent))]
            if stage == "executive":
                extra += _executive_args(plan, spec)
            specs.append(ProcSpec(name, module_argv(_MODULES[stage], *common, "--agent", agent,
                                                    *extra), spec.max_restarts(stage)))
    return specs


def _shared_specs(plan: Plan) -> dict[str, ProcSpec | None]:
    """Agent id -> the process its stages share with the next `plan.agents_per_process - 1`
    agents' (agents/processes/shared.py) for the first agent of each group, None for the
    others."""
    from tools.records import summary

    agents = [a for a in plan.scenario.agents if f"{a.id}.perception" in plan.local]
    out: dict[str, ProcSpec | None] = {}
    size = plan.agents_per_process
    for i in range(0, len(agents), size):
        group, name = agents[i:i + size], f"agents{i // size + 1}"
        specs = [AgentSetup(run=plan.run, agent=a.id, program=str(a.program.resolve()),
                            state=str(summary.state_file(plan.run_dir, a.id)),
                            learned_out=str(summary.learned_file(plan.run_dir, a.id)),
                            swapped=str(summary.swapped_file(plan.run_dir, a.id)),
                            learned=plan.learned, solver=a.solver,
                            mechanism=a.mechanism).to_json()
                 for a in group]
        argv = module_argv("agents.processes.shared", "--run", plan.run,
                           *bus_config(plan, name).to_args(), "--name", name,
                           "--agents", json.dumps(specs))
        restarts = min(a.max_restarts(s) for a in group for s in AGENT_STAGES)
        out.update({a.id: None for a in group})
        out[group[0].id] = ProcSpec(name, argv, restarts)
    return out


def _executive_args(plan: Plan, spec: AgentSpec) -> list[str]:
    """Each executive keeps its engine state and learned skills in the run folder
    (summary.state_file, summary.learned_file), starting from `plan.learned` if given."""
    from tools.records import summary

    return ["--state", str(summary.state_file(plan.run_dir, spec.id)),
            "--learned-out", str(summary.learned_file(plan.run_dir, spec.id)),
            *(["--learned", plan.learned] if plan.learned else []),
            *([] if spec.solver else ["--no-solver"]),
            *(["--mechanism", spec.mechanism] if spec.mechanism != "means-ends" else [])]


def check_secrets(plan: Plan) -> None:
    """Raise PlanError when the secrets folder lacks a file a local process needs."""
    if plan.secrets is None:
        return
    try:
        plan.secrets.check([*plan.local, "launch", "operator"])
    except FileNotFoundError as exc:
        raise PlanError(f"--secrets: {exc}") from exc


def claim_run_dir(run: str, run_dir: Path, given: bool, name: str, secure: bool
                  ) -> tuple[str, Path]:
    """Make the run's new folder, which no other launch can then take: a launch never writes
    into an earlier run's folder (a second `--run r1` would overwrite the
    first run's trace and record and replay its executive's state). A `--run` id whose
    folder exists is refused, not renamed: the id is what the user's tools (`goal post --run`,
    `explain`) will ask for, so a launch under another id would answer them with another
    run; a generated id that is taken is drawn again."""
    while True:
        try:
            run_dir.mkdir(parents=True, mode=0o700 if secure else 0o777)
            return run, run_dir
        except OSError as exc:
            if not isinstance(exc, FileExistsError):
                raise PlanError(f"cannot make the run folder {run_dir}: "
                                f"{exc.strerror or exc}") from None
            if given:
                raise PlanError(f"--run {run}: the folder {run_dir} holds an earlier run, and "
                                f"a launch never writes into one; give another id, or move "
                                f"that folder away first") from None
        run = f"{name}-{secrets.token_hex(3)}"
        run_dir = run_dir.with_name(run)
