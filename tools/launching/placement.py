"""How a launch places its agents' stages in processes: ``--agents-per-process K|auto`` read,
``auto`` turned into K for this machine's CPUs (tools/launching/cpus.py, run_plan.per_core),
and the line that tells the user the layout."""

from __future__ import annotations

import click

from tools.launching.cpus import usable_cores
from tools.launching.run_plan import agent_processes, per_core


class PerProcess(click.ParamType):
    """``--agents-per-process``: a count K >= 0, or ``auto`` (run_plan.per_core)."""

    name = "K|auto"

    def convert(self, value: object, param: click.Parameter | None,
                ctx: click.Context | None) -> int | str:
        if value == "auto" or (isinstance(value, int) and value >= 0):
            return value
        text = str(value).strip()
        if text.isdigit():
            return int(text)
        self.fail(f"{value!r} is not a count of agents (0, 1, 2, ...) or auto", param, ctx)


def placement_of(asked: int | str, agents: int) -> tuple[int, int]:
    """(K, CPUs) for ``--agents-per-process``: K as given (CPUs 0), or for ``auto`` K that
    spreads the agents over the CPUs this launch may use, and how many those are."""
    if asked != "auto":
        return int(asked), 0
    cpus = usable_cores()
    return (per_core(agents, cpus) if agents else 0), cpus


def layout_line(agents: int, per_process: int, cpus: int) -> str:
    """The line saying how the agents' stages share processes (``cpus``: how many
    ``--agents-per-process auto`` spread them over, 0 when K was given)."""
    why = f" (--agents-per-process auto: {cpus} CPUs)" if cpus else ""
    if per_process == 1 or agents == 1:
        return f"each agent's three stages in one process: {count_of(agents, 'process')}{why}"
    processes = count_of(agent_processes(agents, per_process), "process")
    return f"{count_of(agents, 'agent')} in {processes} of up to {per_process} agents each{why}"


def count_of(n: int, noun: str) -> str:
    """``n`` and the noun, plural unless n is 1 ("1 process", "2 processes")."""
    return f"{n} {noun}" if n == 1 else f"{n} {noun}{'es' if noun.endswith('s') else 's'}"
