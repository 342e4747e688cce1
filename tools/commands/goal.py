"""`teleo goal post|list|cancel|priority`: talk to the goal-entry process of a running launch.

The launch is found through the run registry (tools/runs/runfile.py; `--run RUN` when several
run), so no bus flags are needed.
Each command is one query on teleo/<run>/agent/<agent>/goals (GoalRequest -> GoalReply);
the goal-entry process validates a post against the agent's program and answers with the
reason when it refuses it. A posted goal takes effect at the next cycle the goal-entry
process publishes. `post --wait` then follows the goal to its end (tools/commands/goal_wait.py).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

import click

from agents.processes.goal_store import MAX_PRIORITY
from tools.runs import runfile

if TYPE_CHECKING:
    from bus.node import Node

QUERY_TIMEOUT = 5.0  # [s]


@contextmanager
def _session(run: str | None, agent: str | None) -> Iterator[tuple[runfile.RunInfo, Node,
                                                                  Callable]]:
    """(the run, an open node, ask) for the commands' requests: ask(op, agent, goal=,
    priority=, goal_id=, force=) sends one GoalRequest and returns the reply. Bus errors
    become ClickExceptions (the goal-entry process not answering, said so)."""
    from bus import keys
    from bus.errors import BusError, NobodyServing
    from bus.load import overloaded, scaled
    from bus.messages import GoalRequest
    from bus.node import open_node

    info = runfile.locate(run)
    if agent is not None and agent not in info.agents:
        raise click.ClickException(f"run {info.run} has no agent {agent!r} "
                                   f"(agents: {', '.join(info.agents)})")
    try:
        with open_node(runfile.bus_config(info), info.run, "goal-cli") as node:
            def ask(op: str, name: str, goal: str = "", priority: int = 0, goal_id: str = "",
                    force: bool = False, once: bool = False, deadline: int = 0):
                request = GoalRequest(node.envelope(), op, name, goal, priority, goal_id, force,
                                      once, deadline)
                return node.query(keys.goals(info.run, name), request, scaled(QUERY_TIMEOUT))

            yield info, node, ask
    except NobodyServing as exc:
        raise click.ClickException(
            f"run {info.run}: the goal-entry process is not answering ({exc})"
            f"{overloaded(scaled(QUERY_TIMEOUT))}") from exc
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc


def _request(op: str, agent: str | None, goal: str = "", priority: int = 0,
             goal_id: str = "", force: bool = False, run: str | None = None) -> list:
    """Send one GoalRequest per addressed agent; returns the replies (raises ClickException)."""
    with _session(run, agent) as (info, _node, ask):
        return [ask(op, name, goal, priority, goal_id, force)
                for name in _addressed(info, op, agent, goal_id, ask)]


def _addressed(info: runfile.RunInfo, op: str, agent: str | None, goal_id: str,
               ask: Callable) -> list[str]:
    """The agents a request goes to: the one named; else every agent for a list, the only
    agent of a one-agent run, the owner of ``goal_id`` (asked of each agent; for a program
    goal's id, p1..pn, the first agent, whose goal-entry process says what it is); a post
    to a run of several agents must name one (a goal the wrong car adopted would fail,
    unseen)."""
    if agent is not None:
        return [agent]
    if op == "list" or len(info.agents) == 1:
        return list(info.agents) if op == "list" else [info.agents[0]]
    names = ", ".join(info.agents)
    if op == "post":
        raise click.ClickException(f"run {info.run} has {len(info.agents)} agents ({names}): "
                                   f"say which one the goal is for with --agent")
    owners = [name for name in info.agents
              if any(g["id"] == goal_id for g in ask("list", name).goals)]
    if not owners and re.fullmatch(r"p[1-9][0-9]*", goal_id):
        return [info.agents[0]]
    if not owners:
        raise click.ClickException(f"refused: run {info.run} has no goal {goal_id!r} "
                                   f"(agents: {names})")
    return owners[:1]


def _check(reply) -> None:
    if not reply.ok:
        raise click.ClickException(f"refused: {reply.reason}")


def _table(goals) -> None:
    if not goals:
        click.echo("no goals")
        return
    click.echo(f"{'ID':<5} {'AGENT':<8} {'PRIO':>4}  {'STATUS':<10} GOAL")
    for g in goals:
        note = f"  -- {g['note']}" if g.get("note") else ""   # why: impasse, failed
        click.echo(f"{g['id']:<5} {g.get('agent', ''):<8} {g['priority']:>4}  "
                   f"{g['status']:<10} {g['goal']}{note}")


@click.group()
def goal() -> None:
    """Post, list, cancel and reprioritise goals of a running launch.

    Priorities: the program's own goals have priorities 1..n (p1..pn, in file order; in the
    driving program the laws); a goal ranks after every goal of priority <= its own. A
    priority below n would rank a user goal above some of them (a car breaking a law for
    an errand), so it is refused unless --force."""


_PRIORITY = click.IntRange(1, MAX_PRIORITY)
_FORCE = click.option("--force", is_flag=True,
                      help="Accept a priority that ranks the goal above the program's own "
                           "goals (refused otherwise).")


@goal.command()
@click.argument("text", metavar="GOAL")
@click.option("--priority", "-p", type=_PRIORITY, default=100, show_default=True,
              help="Rank: the goal goes after every goal of priority <= P (lower = sooner).")
@click.option("--agent", "-a", help="Agent (needed when the run has several).")
@_FORCE
@click.option("--once", is_flag=True,
              help="Drop the goal when it is achieved (not kept as a maintenance goal, "
                   "pursued again should it stop holding).")
@click.option("--deadline", type=click.IntRange(1, 100_000_000), default=None,
              metavar="CYCLES", help="Fail the goal, with that reason, unless it is achieved "
                                     "within CYCLES cycles.")
@click.option("--wait", "-w", is_flag=True,
              help="Follow the goal to its end, a line at each change; exit 0 achieved, 1 "
                   "failed, 3 cancelled by another or the run ended, 124 --timeout, 130 "
                   "Ctrl-C.")
@click.option("--timeout", type=click.FloatRange(min=0, min_open=True), default=None,
              metavar="S", help="With --wait: give up waiting after S seconds (the goal "
                                "stays posted; exit 124).")
@click.option("--cancel-on-interrupt", is_flag=True,
              help="With --wait: Ctrl-C cancels the goal without asking (a terminal is "
                   "asked; without one the goal stays posted).")
@runfile.run_option
@runfile.quiet_option
def post(text: str, priority: int, agent: str | None, force: bool, once: bool,
         deadline: int | None, wait: bool, timeout: float | None, cancel_on_interrupt: bool,
         run_id: str | None) -> None:
    """Post GOAL, such as '(package-delivered PACKET2)'; with --wait, follow it to its end.

    --wait works as ros2 action send_goal --feedback: after the verdict it prints a line at
    each status change of the goal (with the skill path, the problem solver's or the
    planner's current step) until the goal is achieved or fails."""
    from tools.commands.goal_wait import follow, subscribe

    for given, name in ((timeout is not None, "--timeout"),
                        (cancel_on_interrupt, "--cancel-on-interrupt")):
        if given and not wait:
            raise click.UsageError(f"{name} goes with --wait")
    with _session(run_id, agent) as (info, node, ask):
        name = _addressed(info, "post", agent, "", ask)[0]
        inbox = subscribe(node, info.run, name) if wait else None
        reply = ask("post", name, goal=text, priority=priority, force=force, once=once,
                    deadline=deadline or 0)
        _check(reply)
        click.echo(reply.reason or "posted")
        if inbox is None:
            _table(reply.goals)
            return
        follow(info, name, reply.goals[-1], inbox, ask, timeout, cancel_on_interrupt)


@goal.command(name="list")
@click.option("--agent", "-a", help="Only this agent (default: all).")
@click.option("--json", "as_json", is_flag=True,
              help="Print a JSON list of goal objects (id, agent, goal, priority, status, "
                   "posted_cycle, updated_cycle, note).")
@runfile.run_option
@runfile.quiet_option
def list_(agent: str | None, as_json: bool, run_id: str | None) -> None:
    """List the goals with their statuses."""
    goals = []
    for reply in _request("list", agent, run=run_id):
        _check(reply)
        goals.extend(reply.goals)
    if as_json:
        click.echo(json.dumps(goals, indent=1))
    else:
        _table(goals)


@goal.command()
@click.argument("goal_id", metavar="ID")
@click.option("--agent", "-a", help="Agent (default: the one whose goal ID is).")
@click.option("--force", is_flag=True,
              help="Withdraw an achieved goal too (refused otherwise: the agent keeps an "
                   "achieved goal, acting again should it stop holding).")
@runfile.run_option
@runfile.quiet_option
def cancel(goal_id: str, agent: str | None, force: bool, run_id: str | None) -> None:
    """Cancel goal ID."""
    reply = _request("cancel", agent, goal_id=goal_id, force=force, run=run_id)[0]
    _check(reply)
    click.echo(reply.reason or f"cancelled {goal_id}")


@goal.command(context_settings={"ignore_unknown_options": True})  # P = -1: out of range
@click.argument("goal_id", metavar="ID")
@click.argument("new_priority", metavar="P", type=_PRIORITY)
@click.option("--agent", "-a", help="Agent (default: the one whose goal ID is).")
@_FORCE
@runfile.run_option
@runfile.quiet_option
def priority(goal_id: str, new_priority: int, agent: str | None, force: bool,
             run_id: str | None) -> None:
    """Give goal ID the priority P."""
    reply = _request("priority", agent, priority=new_priority, goal_id=goal_id,
                     force=force, run=run_id)[0]
    _check(reply)
    click.echo(reply.reason or f"{goal_id} now has priority {new_priority}")


commands = [goal]
