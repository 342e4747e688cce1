"""What each agent's mechanisms did, for the run summary (tools/records/summary.py): what a
launch left of each agent in its run folder (the executive's state file `state-AGENT.json`,
the learned skills `learned-AGENT.tlp`, its last memory as the world's trace recorded it),
handed to every mechanism's report, which makes its own entry of it
(tools/records/mechanism_reports.py: the means-ends learner's "learned", SCS's "bodies",
ROGUE's "planner"); and how a summary of
many agents stays readable: natural order (A2 before A10), alike lines folded, the cycle
time's stages summed beyond the largest.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

import click

# agents.lang is imported where it is used: a command that reads summaries (`teleo stop`,
# `teleo ps`) starts without the engine (tests/tools/test_cli_startup.py).


def agent_sections(run_dir: Path, counters: dict[str, dict[str, int]],
                   memory: dict[str, Any]) -> dict[str, Any]:
    """The summary's entries of the mechanisms ("learned", "bodies", "planner")."""
    from tools.records.mechanism_reports import AgentRecord, summary_sections

    states = {path.stem.removeprefix("state-"): (read_json_file(path) or {}).get("state", {})
              for path in sorted(run_dir.glob("state-*.json"))}
    learned = {path.stem.removeprefix("learned-"): path
               for path in sorted(run_dir.glob("learned-*.tlp"))}
    agents = {name: AgentRecord(
        state=states.get(name) or {}, memory=memory.get(name) or {},
        learned=learned[name].read_text(errors="replace") if name in learned else None,
        learned_file=str(learned.get(name, "")), counters=counters.get(name, {}))
        for name in {*states, *learned, *memory}}
    return natural_sections(summary_sections(agents))


def natural(name: str) -> list[Any]:
    """A sort key that puts A2 before A10 (not A0, A1, A10, ...)."""
    return [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", name)]


def natural_sections(sections: dict[str, Any]) -> dict[str, Any]:
    """Each mechanism's entry with its agents in natural order."""
    return {key: dict(sorted(entry.items(), key=lambda kv: natural(kv[0])))
            if isinstance(entry, dict) else entry for key, entry in sections.items()}


def set_aside(run_dir: Path) -> dict[str, Any]:
    """The summary's "set_aside": the files of the run folder an executive could not read
    back after a restart (a state or learned-skills file), kept under a new name
    (agents/processes/persist.py set_aside) while the run went on."""
    from agents.processes.persist import set_aside_files

    return {"set_aside": [str(p) for p in set_aside_files(run_dir)]}


def echo_agents(summary: dict[str, Any]) -> None:
    """Print those entries for a person, many agents' like lines folded (fold_lines),
    and the files set aside."""
    from tools.records.mechanism_reports import summary_lines

    for line in fold_lines(summary_lines(summary), summary_agents(summary)):
        click.echo(line)
    for path in summary.get("set_aside", ()):
        click.echo(f"  SET ASIDE: {path} could not be read back after a restart; kept, and "
                   "the run went on without it")


FOLD_FROM = 4   # agents whose lines read alike are told in one line from this many on


def summary_agents(summary: dict[str, Any]) -> list[str]:
    """The agents a summary tells of, in natural order."""
    names = {*summary.get("law_violations", {}), *summary.get("counters", {})}
    return sorted(names, key=natural)


def fold_lines(lines: list[str], agents: list[str]) -> list[str]:
    """``lines`` with the lines of at least FOLD_FROM agents that differ only in the
    agent's name told once: `  A0..A49 (50 agents): deliveries 0, law violations 0` (a
    run of 50 cars printed 100 such lines); with fewer agents, ``lines`` as they are."""
    if len(agents) < FOLD_FROM:
        return lines
    groups: dict[str, list[str]] = {}
    for line in lines:
        name = next((a for a in agents if line.startswith(f"  {a}: ")), None)
        if name is None:
            groups.setdefault(line, [])
            continue
        template = re.sub(rf"(?<!\w){re.escape(name)}(?!\w)", "{agent}",
                          line[len(name) + 4:])
        groups.setdefault(template, []).append(name)
    out = []
    for template, names in groups.items():
        if not names:
            out.append(template)
        elif len(names) < FOLD_FROM:
            out += [f"  {n}: {template.replace('{agent}', n)}" for n in names]
        else:
            out.append(f"  {names_text(names)} ({len(names)} agents): {template}")
    return out


def names_text(names: list[str]) -> str:
    """Names in natural order, each run of consecutive numbers with one prefix as
    `A0..A49`: `A0..A9, B1, C3..C5`."""
    parts: list[list[Any]] = []   # [prefix, first, last] or [name]
    for name in sorted(names, key=natural):
        m = re.fullmatch(r"(.*?)(\d+)", name)
        last = parts[-1] if parts else None
        if m and last and len(last) == 3 and last[0] == m[1] and last[2] + 1 == int(m[2]):
            last[2] = int(m[2])
        else:
            parts.append([m[1], int(m[2]), int(m[2])] if m else [name])
    return ", ".join(p[0] if len(p) == 1 else f"{p[0]}{p[1]}" if p[1] == p[2] else
                     f"{p[0]}{p[1]}..{p[0]}{p[2]}" if p[2] > p[1] + 1 else
                     f"{p[0]}{p[1]}, {p[0]}{p[2]}" for p in parts)


def read_json_file(path: Path) -> Any:
    """The JSON in `path`, or None when it is absent or not bounded JSON (any bytes)."""
    from agents.lang import LangError
    from agents.lang.core.limits import read_json

    try:
        text = path.read_bytes().decode("utf-8", errors="replace")
        return read_json(text, str(path), max_chars=64 << 20, max_string=1 << 20)
    except (OSError, LangError):
        return None


SHARES_SHOWN = 5   # of many stages, the largest shares named; the rest summed


def shares_text(shares: dict[str, float]) -> list[str]:
    """The cycle time's shares as `name pct %`; of more than 2 * SHARES_SHOWN agent stages
    (50 agents have 150), the SHARES_SHOWN largest and the others summed."""
    fixed = ("world", "goals", "bus and waits")
    stages = {k: v for k, v in shares.items() if k not in fixed}
    if len(stages) <= 2 * SHARES_SHOWN:
        return [f"{name} {pct} %" for name, pct in shares.items()]
    top = sorted(stages, key=lambda k: -stages[k])[:SHARES_SHOWN]
    rest = round(sum(v for k, v in stages.items() if k not in top), 1)
    return [f"{name} {pct} %" for name, pct in shares.items()
            if name in top or name in fixed and name != "bus and waits"] \
        + [f"{len(stages) - len(top)} other stages {rest} %",
           f"bus and waits {shares.get('bus and waits', 0.0)} %"]
