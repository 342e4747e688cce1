"""The `[world]` table of a pddl scenario: `domain_file` and `problem_file` (paths; a relative
one is looked up as a program's is, beside the scenario first: world/scenario_types.py), read
into a Task (task.py). Every error is a ConfigError naming the key or the file:line:col."""

from __future__ import annotations

from typing import Any

from world.errors import ConfigError
from world.pddl.files import load_task
from world.pddl.task import Task

KEYS = ("domain_file", "problem_file")
_KNOWN = KEYS   # the keys docs/scenarios.md documents (tests/tools/test_docs.py)


def load_pddl_config(table: dict[str, Any]) -> Task:
    """The Task the table names (an empty table: the Sussman anomaly, example.py); raises
    ConfigError (one line)."""
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise ConfigError(f"[world] {unknown[0]}: not a key of the pddl world (keys: "
                          f"{', '.join(KEYS)})")
    if not table:
        from world.pddl import example

        return load_task(example.DOMAIN_NAME, example.PROBLEM_NAME,
                         (example.DOMAIN, example.PROBLEM))
    for key in KEYS:
        value = table.get(key)
        if not isinstance(value, str) or not value:
            raise ConfigError(f"[world] {key}: expected the path of a PDDL file, got "
                              f"{value!r}")
    return load_task(table["domain_file"], table["problem_file"])
