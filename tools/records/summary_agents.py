"""What each agent's mechanisms did, for the run summary (tools/records/summary.py): what a
launch left of each agent in its run folder (the executive's state file `state-AGENT.json`,
the learned skills `learned-AGENT.tlp`, its last memory as the world's trace recorded it),
handed to every registered mechanism, which makes its own entry of it (agents/lang/registry.py:
the means-ends learner's "learned", SCS's "bodies", ROGUE's "planner").
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import click

# agents.lang is imported where it is used: a command that reads summaries (`teleo stop`,
# `teleo ps`) starts without the engine (tests/tools/test_cli_startup.py).


def agent_sections(run_dir: Path, counters: dict[str, dict[str, int]],
                   memory: dict[str, Any]) -> dict[str, Any]:
    """The summary's entries of the mechanisms ("learned", "bodies", "planner")."""
    from agents.lang.registry import AgentRecord, summary_sections

    states = {path.stem.removeprefix("state-"): (read_json_file(path) or {}).get("state", {})
              for path in sorted(run_dir.glob("state-*.json"))}
    learned = {path.stem.removeprefix("learned-"): path
               for path in sorted(run_dir.glob("learned-*.tlp"))}
    agents = {name: AgentRecord(
        state=states.get(name) or {}, memory=memory.get(name) or {},
        learned=learned[name].read_text(errors="replace") if name in learned else None,
        learned_file=str(learned.get(name, "")), counters=counters.get(name, {}))
        for name in {*states, *learned, *memory}}
    return summary_sections(agents)


def set_aside(run_dir: Path) -> dict[str, Any]:
    """The summary's "set_aside": the files of the run folder an executive could not read
    back after a restart (a state or learned-skills file), kept under a new name
    (agents/processes/persist.py set_aside) while the run went on."""
    from agents.processes.persist import set_aside_files

    return {"set_aside": [str(p) for p in set_aside_files(run_dir)]}


def echo_agents(summary: dict[str, Any]) -> None:
    """Print those entries for a person, and the files set aside."""
    from agents.lang.registry import summary_lines

    for line in summary_lines(summary):
        click.echo(line)
    for path in summary.get("set_aside", ()):
        click.echo(f"  SET ASIDE: {path} could not be read back after a restart; kept, and "
                   "the run went on without it")


def read_json_file(path: Path) -> Any:
    """The JSON in `path`, or None when it is absent or not bounded JSON (any bytes)."""
    from agents.lang import LangError
    from agents.lang.core.limits import read_json

    try:
        text = path.read_bytes().decode("utf-8", errors="replace")
        return read_json(text, str(path), max_chars=64 << 20, max_string=1 << 20)
    except (OSError, LangError):
        return None
