"""`teleo graph PROGRAM` and `teleo graph --run RUN`: pictures of a program's goals, skills and
concepts (tools/records/program_graph.py, as py_trees renders a tree) and of a running run's
processes and keys (tools/records/run_graph.py, as ROS 2's rqt_graph), written as SVG or PNG
(tools/records/drawing.py); `--json` prints the nodes and edges.

    teleo graph programs/blocks.tlp --out blocks.svg
    teleo graph scenarios/errands_demo.toml --agent ME --json
    teleo graph --run driving-demo-ab12cd --out run.png
    teleo graph --run out/runs/blocks-figure3-sim-0c1947 --json    (a run that has ended)
"""

from __future__ import annotations

import json
import os
import sys
import time

import click

from tools.commands.lang import include_option
from tools.paths import OutputPath, suffix_check
from tools.records.drawing import PICTURE_SUFFIXES, Graph, write_picture

graph_check = suffix_check(PICTURE_SUFFIXES, "a graph")
PRESENCE_WAIT = 3.0  # [s] at most for the run's liveliness tokens to be seen
PRESENCE_QUIET = 0.5  # [s] with no token appearing after which all are taken as seen


def _fail(message: str) -> None:
    click.echo(message if message.startswith("Error") else f"Error: {message}", err=True)
    sys.exit(1)


def program_of(path: str, includes: tuple[str, ...], agent: str | None):
    """The program of ``path`` (a program file, or a scenario's agent's program), loaded as
    `teleo check` loads it; exits 1 with the loader's first `file:line:col` error."""
    from agents.lang import ProgramError, load_program
    from tools.commands.check import is_scenario
    from tools.commands.examples import scenario_path

    path = path if path.endswith(".tlp") else scenario_path(path)
    if not is_scenario(path):
        if agent is not None:
            raise click.UsageError("--agent names an agent of a scenario: PROGRAM is a program")
        try:
            return load_program(path, *includes)
        except ProgramError as exc:
            _fail(str(exc.errors[0] if exc.errors else exc.diagnostics[0]))
    from tools.commands.scenario_check import load_checked
    from world.run_scenario import ScenarioError

    try:
        scenario, programs = load_checked(path)
    except ScenarioError as exc:
        first = str(exc.errors[0])
        _fail(first if first.startswith(f"{path}:") else f"{path}: {first}")
    if agent is None and len(programs) != 1:
        raise click.UsageError(f"{path} has agents {', '.join(programs)}: choose one with "
                               "--agent")
    agent = agent if agent is not None else next(iter(programs))
    if agent not in programs:
        raise click.UsageError(f"{path} has no agent {agent!r}; agents: {', '.join(programs)}")
    return programs[agent]


def settled(presence) -> set[str]:
    """The processes up, once no token has appeared for PRESENCE_QUIET seconds (the tokens
    of a run come in one by one) or PRESENCE_WAIT has passed."""
    end = time.monotonic() + PRESENCE_WAIT
    seen = set(presence.snapshot())
    while time.monotonic() < end:
        presence.wait_change(PRESENCE_QUIET)
        now = set(presence.snapshot())
        if now == seen and now:
            break
        seen = now
    return seen


class _NotRunning(Exception):
    """No launch of that run is running here (the message says where it looked)."""


def live_graph(run: str, stats: bool = False) -> Graph:
    """The graph of the running launch ``run`` from the processes whose liveliness tokens are
    up; _NotRunning when none is registered, exit 1 when none of its processes is up."""
    from bus.errors import BusError
    from bus.node import open_node
    from tools.records.run_graph import run_graph
    from tools.runs import runfile

    try:
        info = runfile.find(run)
        with open_node(runfile.bus_config(info), info.run, f"graph-{os.getpid()}"
                       ) as node:
            alive = settled(node.presence)
    except runfile.NoRunningLaunch as exc:
        raise _NotRunning(str(exc)) from None
    except BusError as exc:
        _fail(f"run {run}: cannot reach its router: {exc}")
    if not alive:
        _fail(f"run {info.run}: no process of it is up (no liveliness token under "
              f"teleo/{info.run}/proc/*)")
    return run_graph(info.run, set(alive), stats)


def record_graph(run: str, stats: bool, running: str) -> Graph:
    """The graph of a run that has ended, from its record (its messages' senders and keys);
    exit 1 naming both what was looked for when there is none (``running``: why no launch)."""
    from tools.records.run_graph import run_graph
    from tools.records.run_record import RecordError, RunRecord, locate

    try:
        rec = RunRecord(locate(run))
        sent: dict[str, set[str]] = {}
        for key, record in rec.records():
            sender = (record.get("env") or {}).get("sender")
            if isinstance(sender, str) and sender:
                sent.setdefault(sender, set()).add(key)
    except RecordError as exc:
        _fail(f"{running}; nor is there a record of it ({exc})")
    return run_graph(rec.run, set(sent), stats, sent)


@click.command()
@click.argument("program", required=False)
@click.option("--run", "run_id", default=None, metavar="RUN",
              help="Draw this run's processes and keys instead (as rqt_graph): a running "
                   "launch, else its record.")
@click.option("--stats", is_flag=True,
              help="With --run: draw the keys of each process's compute times too.")
@click.option("--agent", default=None,
              help="With a scenario as PROGRAM: whose program (default: the only agent).")
@click.option("--out", "out", type=OutputPath(graph_check), default=None,
              help="Write the picture here: .svg or .png.")
@click.option("--json", "as_json", is_flag=True, help="Print the nodes and edges as JSON.")
@include_option
def graph(program: str | None, run_id: str | None, stats: bool, agent: str | None,
          out: str | None, as_json: bool, includes: tuple[str, ...]) -> None:
    """Draw a program's goals, skills and concepts, or a running launch's processes and keys.

    PROGRAM is a program file or a scenario (its agent's program, --agent): goals point to
    the skills that achieve them, skills to their subgoals' skills (an SCS body to its
    steps), concepts to the concepts they are defined from (dashed through `not`).
    Primitive skills and percept-only concepts are drawn apart. `--run RUN` draws the
    processes of a running launch that are up (liveliness) and the keys each publishes
    and subscribes to (bus/security.py's grants); for a run that has ended, its record's
    senders and the keys they sent on. Name --out F.svg|F.png, --json or both."""
    if stats and run_id is None:
        raise click.UsageError("--stats goes with --run")
    if (program is None) == (run_id is None):
        raise click.UsageError("name a PROGRAM or --run RUN (one of them)")
    if out is None and not as_json:
        raise click.UsageError("name --out F.svg|F.png, or --json for the nodes and edges")
    if run_id is not None:
        if agent is not None or includes:
            raise click.UsageError("--agent and -I go with a PROGRAM, not --run")
        try:
            g = live_graph(run_id, stats)
        except _NotRunning as exc:
            g = record_graph(run_id, stats, str(exc))
    else:
        from tools.records.program_graph import program_graph

        g = program_graph(program_of(program, includes, agent), program)
    if out is not None:
        write_picture(g, out)
        if not as_json:
            click.echo(f"{out}: {len(g.nodes)} nodes, {len(g.edges)} edges")
    if as_json:
        click.echo(json.dumps(g.to_json(), indent=1))


commands = [graph]
