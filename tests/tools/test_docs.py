"""The docs say what exists (issue 12, item 15): docs/scenarios.md documents every key of each
world's `[world]` table and every event kind itself; every `teleo COMMAND` the README and the
docs name is a command; every file they point to is in the repository."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import click
import pytest

from tools.cli import cli
from world.domain import DOMAINS, get_domain

ROOT = Path(__file__).resolve().parents[2]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
        *sorted((ROOT / "world").glob("*/percepts.md"))]
CONFIGS = {"driving": "world.driving.config", "blocks": "world.blocks.config",
           "office": "world.office.config", "pddl": "world.pddl.config"}
HEADINGS = {"driving": "## Driving", "blocks": "## The Blocks World", "office": "## Office",
            "pddl": "## PDDL"}


def section(text: str, heading: str) -> str:
    start = text.index(heading)
    end = text.find("\n## ", start + 1)
    return text[start:end if end > 0 else None]


@pytest.mark.parametrize("domain", DOMAINS)
def test_each_worlds_table_and_events_are_documented_in_scenarios_md(domain):
    text = section((ROOT / "docs" / "scenarios.md").read_text(), HEADINGS[domain])
    keys = importlib.import_module(CONFIGS[domain])._KNOWN
    missing = sorted(k for k in keys if f"`{k}`" not in text and f"{k} =" not in text)
    assert missing == [], f"{domain}: keys not documented: {missing}"
    kinds = [k for k in get_domain(domain).event_kinds if f'"{k}"' not in text
             and f"`{k}`" not in text]
    assert kinds == [], f"{domain}: event kinds not documented: {kinds}"


def test_every_teleo_command_the_docs_name_exists():
    named = set()
    for path in DOCS:
        named |= {m for m in re.findall(r"`teleo ([a-z]+)", path.read_text())}
    assert named - set(cli.list_commands(None)) == set()
    assert {"check", "simulate", "launch", "goal", "event", "inspect"} <= named


def test_every_file_the_docs_point_to_exists():
    pattern = re.compile(r"\b((?:agents|bus|world|tools|tests|docs|programs|scenarios|bench)"
                         r"/[\w./-]+\.(?:py|md|tlp|toml))")
    missing = {(path.name, ref) for path in DOCS for ref in pattern.findall(path.read_text())
               if not (ROOT / ref).exists() and ref != "scenarios/x.toml"}   # an example name
    assert missing == set()


def _readme_rows() -> list[tuple[click.Command, str]]:
    """(command, the row's description) of each row of the README's command table."""
    rows = []
    for line in (ROOT / "README.md").read_text().splitlines():
        match = re.match(r"\| `teleo ([a-z]+)(?: ([a-z]+))?[^`]*`.*?\| (.*) \|$", line)
        if match and match.group(1) in cli.commands:
            command = cli.commands[match.group(1)]
            sub = getattr(command, "commands", {}).get(match.group(2) or "")
            rows.append((sub or command, match.group(3)))
    return rows


def test_readme_rows_say_a_flag_prints_not_that_it_writes_a_file():
    """Issue 24, #19: "`--percepts` writes that cycle's percepts" sent a user to give it a
    file; it is a flag that prints to stdout."""
    rows = _readme_rows()
    assert len(rows) >= 15
    wrong = [(command.name, option.opts[0]) for command, text in rows
             for option in command.params
             if isinstance(option, click.Option) and option.is_flag
             and re.search(rf"`{re.escape(option.opts[0])}` writes", text)]
    assert wrong == []
