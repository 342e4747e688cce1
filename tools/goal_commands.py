"""`teleo goal post|list|cancel|priority`: talk to the goal-entry process of a running launch.

The launch is found through its run file (tools/runfile.py), so no bus flags are needed.
Each command is one query on teleo/<run>/agent/<agent>/goals (GoalRequest -> GoalReply);
the goal-entry process validates a post against the agent's program and answers with the
reason when it refuses it. A posted goal takes effect at the next cycle the goal-entry
process publishes.
"""

from __future__ import annotations

import click

from agents.processes.goal_store import MAX_PRIORITY
from tools import runfile

QUERY_TIMEOUT = 5.0  # [s]


def _request(op: str, agent: str | None, goal: str = "", priority: int = 0,
             goal_id: str = "") -> list:
    """Send one GoalRequest per addressed agent; returns the replies (raises ClickException)."""
    from bus import keys
    from bus.config import BusConfig
    from bus.errors import BusError, NobodyServing
    from bus.messages import GoalRequest
    from bus.node import open_node

    try:
        info = runfile.find()
    except runfile.NoRunningLaunch as exc:
        raise click.ClickException(str(exc)) from exc
    agents = list(info.agents) if agent is None and op == "list" else [agent or info.agents[0]]
    if agents[0] not in info.agents:
        raise click.ClickException(f"run {info.run} has no agent {agents[0]!r} "
                                   f"(agents: {', '.join(info.agents)})")
    cfg = BusConfig(mode="client", connect=(info.endpoint,), listen=())
    replies = []
    try:
        with open_node(cfg, info.run, "goal-cli") as node:
            for name in agents:
                request = GoalRequest(node.envelope(), op, name, goal, priority, goal_id)
                replies.append(node.query(keys.goals(info.run, name), request, QUERY_TIMEOUT))
    except NobodyServing as exc:
        raise click.ClickException(
            f"run {info.run}: the goal-entry process is not answering ({exc})") from exc
    except BusError as exc:
        raise click.ClickException(str(exc)) from exc
    return replies


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
    """Post, list, cancel and reprioritise goals of a running `teleo launch`."""


_PRIORITY = click.IntRange(1, MAX_PRIORITY)


@goal.command()
@click.argument("text", metavar="GOAL")
@click.option("--priority", "-p", type=_PRIORITY, default=100, show_default=True,
              help="Rank: the goal goes after every goal of priority <= P (lower = sooner).")
@click.option("--agent", "-a", help="Agent (default: the run's first agent).")
def post(text: str, priority: int, agent: str | None) -> None:
    """Post GOAL, e.g. '(package-delivered PACKET2)'."""
    reply = _request("post", agent, goal=text, priority=priority)[0]
    _check(reply)
    click.echo(reply.reason or "posted")
    _table(reply.goals)


@goal.command(name="list")
@click.option("--agent", "-a", help="Only this agent (default: all).")
def list_(agent: str | None) -> None:
    """List the goals with their statuses."""
    goals = []
    for reply in _request("list", agent):
        _check(reply)
        goals.extend(reply.goals)
    _table(goals)


@goal.command()
@click.argument("goal_id", metavar="ID")
@click.option("--agent", "-a", help="Agent (default: the run's first agent).")
def cancel(goal_id: str, agent: str | None) -> None:
    """Cancel goal ID."""
    reply = _request("cancel", agent, goal_id=goal_id)[0]
    _check(reply)
    click.echo(reply.reason or f"cancelled {goal_id}")


@goal.command()
@click.argument("goal_id", metavar="ID")
@click.argument("new_priority", metavar="P", type=_PRIORITY)
@click.option("--agent", "-a", help="Agent (default: the run's first agent).")
def priority(goal_id: str, new_priority: int, agent: str | None) -> None:
    """Give goal ID the priority P."""
    reply = _request("priority", agent, priority=new_priority, goal_id=goal_id)[0]
    _check(reply)
    click.echo(reply.reason or f"{goal_id} now has priority {new_priority}")


commands = [goal]
