"""`teleo explain RUN`: why an agent did what it did, from a run record
(tools/records/run_record.py).

    teleo explain RUN [--agent A] [--cycle N]       the decision of cycle N as a tree
    teleo explain RUN --goal g2                     when g2 became active, suspended, achieved
    teleo explain RUN --percepts --cycle N > f.txt  cycle N's percepts, as `teleo step` reads them

A run whose agent was given another program while it ran (`teleo program load`) says which
program each decision was made with, and the swap's verdict at the cycle it came.

RUN is a run folder, a run id under the runs folder, or an .mcap file.
"""

from __future__ import annotations

import json
import re
from typing import Any

import click

from tools.records.run_record import GoalHistory, RecordError, RunRecord, locate
from tools.records.tree import decision_tree, fold, render_text, to_json

PROGRAM_GOAL = re.compile(r"p\d+")  # the engine's ids of program goals (Engine.initial_state)


def _open(run: str, agent: str | None, goal_id: str | None = None) -> tuple[RunRecord, str]:
    """The record of ``run`` and the agent asked about: the one named, the only one, or the
    one whose goal ``goal_id`` is (goal ids are the run's)."""
    try:
        rec = RunRecord(locate(run))
        agents = rec.agents()
    except RecordError as exc:
        raise click.ClickException(str(exc)) from exc
    if agent is None and goal_id is not None and len(agents) > 1:
        owners = [a for a in agents if any(g.get("id") == goal_id for i in
                                           rec.by_cycle("intention", a).values()
                                           for g in i["decision"].get("goals", ()))]
        agent = owners[0] if len(owners) == 1 else None
    if agent is None:
        if len(agents) != 1:
            raise click.UsageError(f"run {rec.run} has agents {', '.join(agents) or 'none'}: "
                                   "choose one with --agent")
        agent = agents[0]
    elif agent not in agents:
        raise click.UsageError(f"run {rec.run} has no agent {agent!r}; agents: "
                               f"{', '.join(agents)}")
    return rec, agent


def _of_cycle(rec: RunRecord, kind: str, agent: str, cycle: int | None) -> tuple[int, dict]:
    """The record of `kind` of `cycle` (default: the last recorded); UsageError if absent."""
    by_cycle = rec.by_cycle(kind, agent)
    if not by_cycle:
        raise click.ClickException(f"run {rec.run}: no {kind} of {agent} recorded")
    cycle = max(by_cycle) if cycle is None else cycle
    if cycle not in by_cycle:
        raise click.UsageError(f"run {rec.run}: no {kind} of {agent} at cycle {cycle}; "
                               f"recorded cycles {min(by_cycle)}..{max(by_cycle)}")
    return cycle, by_cycle[cycle]


def goal_history(rec: RunRecord, agent: str, goal_id: str) -> list[dict[str, Any]]:
    """Every status change of one goal, from the intentions (with the engine's notes) and the
    goal lists (a cancellation); a change seen only after a gap in the record has "after"
    (tools/records/run_record.py GoalHistory)."""
    history, states = GoalHistory(), rec.state_cycles()
    for _, record in rec.kinds_of(("intention", "goal-list"), agent):
        history.feed(record, states.__contains__)
    return history.changes[agent].get(goal_id, [])


def percept_file(rec: RunRecord, agent: str, cycle: int, intention: dict | None) -> str:
    """The percepts of a cycle as a file for `teleo step` (s-expressions when they read back
    exactly, else JSON lists), headed by comments saying how to replay the decision."""
    from agents.lang import LangError, parse_percepts

    percepts = rec.by_cycle("percepts", agent)[cycle]["percepts"]
    goals = [g for g in (intention or {}).get("decision", {}).get("goals", ())
             if not PROGRAM_GOAL.fullmatch(str(g.get("id")))]
    flags = " ".join(f"--goal '{g['id']}={g['goal']}:{g['priority']}'" for g in goals)
    head = [f"; percepts of {agent} at cycle {cycle} of run {rec.run}",
            f"; replay the decision: teleo step {_ran(rec, agent, cycle)} --percepts FILE "
            f"{flags}".rstrip(),
            "; (user goals as listed that cycle; remembered paths and action outcomes are "
            "not in this file)"]
    text = "\n".join(head + ["(" + " ".join(_atom(v) for v in p) + ")" for p in percepts])
    try:
        if [p.to_list() for p in parse_percepts(text)] == percepts:
            return text + "\n"
    except LangError:
        pass
    return json.dumps(percepts) + "\n"


def _ran(rec: RunRecord, agent: str, cycle: int) -> str:
    ran = program_at(rec, agent, cycle)
    return ran["name"] if ran else _program(rec, agent)


def _program(rec: RunRecord, agent: str) -> str:
    """The agent's program file, from the run's scenario (with the `--set` the run was given)
    when it can still be read."""
    from world.errors import WorldError
    from world.run_scenario import load_scenario

    meta = rec.meta.get("teleo.run", {})
    try:
        overrides = json.loads(meta.get("overrides", "[]"))
        scenario = load_scenario(meta.get("scenario", ""),
                                 [str(o) for o in overrides] if isinstance(overrides, list)
                                 else ())
        return str(next(a.program for a in scenario.agents if a.id == agent))
    except (WorldError, OSError, StopIteration, ValueError):
        return "PROGRAM"


def program_at(rec: RunRecord, agent: str, cycle: int) -> dict[str, Any] | None:
    """The program `agent` ran at `cycle` when the run swapped one in (`teleo program load`:
    the percepts of the cycle it came at carry it), {"name", "since": that cycle, or 0 for
    the scenario's}; None for a run that never swapped one."""
    swaps = sorted((c, r["program"].get("name", "")) for c, r in
                   rec.by_cycle("percepts", agent).items()
                   if isinstance(r.get("program"), dict) and r["program"])
    if not swaps:
        return None
    ran = [(c, name) for c, name in swaps if c <= cycle]
    if not ran:
        return {"name": _program(rec, agent), "since": 0}
    return {"name": ran[-1][1], "since": ran[-1][0]}


def _atom(v: Any) -> str:
    return repr(v) if isinstance(v, float) else str(v)


def _history_text(rec: RunRecord, agent: str, goal_id: str, changes: list[dict]) -> str:
    first = changes[0]
    lines = [f"goal {goal_id} of {agent}: {first['goal']}, priority {first['priority']} "
             f"(run {rec.run})"]
    for c in changes:
        note = f"  -- {c['note']}" if c["note"] else ""
        if "after" in c:  # seen after a gap in the record: at one of these cycles
            note += f"  (at a cycle from {c['after'] + 1} on: the record lacks some before)"
        lines.append(f"  cycle {c['cycle']:>6}  {c['status']:<9}{note}")
    return "\n".join(lines)


@click.command()
@click.argument("run", metavar="RUN")
@click.option("--agent", default=None, help="Whose decisions (default: the only agent).")
@click.option("--cycle", type=int, default=None, help="Which cycle (default: the last).")
@click.option("--goal", "goal_id", default=None, help="Show this goal's history instead.")
@click.option("--percepts", "percepts", is_flag=True,
              help="Print the cycle's percepts as a file `teleo step --percepts` reads.")
@click.option("--brief", is_flag=True,
              help="Fold the skills passed over for goals that do not act into one line.")
@click.option("--json", "as_json", is_flag=True, help="One JSON object, for scripts.")
def explain(run: str, agent: str | None, cycle: int | None, goal_id: str | None,
            percepts: bool, brief: bool, as_json: bool) -> None:
    """Explain a recorded decision: goals with statuses, the skill path with bindings, the
    skills passed over and why (RUN: a run folder, a run id or an .mcap file)."""
    if goal_id is not None and (cycle is not None or percepts):
        raise click.UsageError("--goal shows a goal's whole history: leave out --cycle/--percepts")
    rec, agent = _open(run, agent, goal_id)
    if goal_id is not None:
        changes = goal_history(rec, agent, goal_id)
        if not changes:
            known = sorted({g["id"] for i in rec.by_cycle("intention", agent).values()
                            for g in i["decision"].get("goals", ())})
            raise click.UsageError(f"run {rec.run}: {agent} never had a goal {goal_id!r}; "
                                   f"goals: {', '.join(known)}")
        click.echo(json.dumps({"run": rec.run, "agent": agent, "goal_id": goal_id,
                               "history": changes}, indent=1) if as_json
                   else _history_text(rec, agent, goal_id, changes))
        return
    if percepts:
        cycle, _ = _of_cycle(rec, "percepts", agent, cycle)
        intention = rec.by_cycle("intention", agent).get(cycle)
        click.echo(percept_file(rec, agent, cycle, intention), nl=False)
        return
    cycle, intention = _of_cycle(rec, "intention", agent, cycle)
    ran = program_at(rec, agent, cycle)
    title = f"goals of {agent} at cycle {cycle} (run {rec.run})"
    if ran is not None:
        title += f", program {ran['name']} (from cycle {ran['since']})"
    try:
        tree = decision_tree(intention["decision"], title)
    except (TypeError, KeyError, IndexError, AttributeError, ValueError) as exc:
        # a record is only shape-checked (bus/record.py): a decision that does not read is
        # said, never a traceback
        raise click.ClickException(f"run {rec.run}: the decision of {agent} at cycle {cycle} "
                                   f"does not read ({type(exc).__name__}: {exc})") from None
    tree = fold(tree) if brief else tree
    if as_json:
        click.echo(json.dumps({"run": rec.run, "agent": agent, "cycle": cycle,
                               "program": ran or {"name": _program(rec, agent), "since": 0},
                               "swap": intention.get("swap") or {},
                               "decision": intention["decision"], "tree": to_json(tree)},
                              indent=1))
    else:
        click.echo(render_text(tree))


commands = [explain]
