"""`--set KEY=VALUE`: a field of a scenario changed for one run without editing its file, as
`ros2 launch` takes `key:=value` (`teleo launch`, `teleo simulate`, `teleo check`;
docs/scenarios.md, "Overrides").

KEY is the field's place, table first: `run.cycles`, `world.pedestrians`,
`world.table.columns`. An entry of an array of tables is named by its `id`
(`agents.ME.program`, `world.packages.PACKET1.address`), by its `agent` for the arrays in
`[world]` whose entries have none (`world.cars.ME.along`), or by its number counted from 1,
as the messages count them (`goals.2.priority` is `[[goals]] #2`). A table the file leaves
out is created (`world.pedestrians` in a scenario without `[world]`). A program path is read
from the working directory when the file is there (a path on the command line), else as the
file's own paths are (beside the scenario, then in the folders above it).

VALUE is read as a TOML value (`20`, `2.5`, `true`, `"text"`, `[3, 4]`, `{ agent = "ME" }`),
within the bounds a scenario file is read in (world/toml_text.py). Text that is no TOML value
is the string it spells (`programs/x.tlp`, `realtime`), and so is a value given to a field
that takes a string (`run.name=2026` is the name "2026"). The scenario with every override
applied is then checked exactly as its file would be (world/run_scenario.py), so a value of
the wrong kind, range or name is refused as it would be in the file.
"""

from __future__ import annotations

import copy
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from world.errors import WorldError
from world.toml_text import NOT_A_VALUE, TomlTextError, toml_value

TABLES = ("run", "world", "agents", "goals", "events")
ARRAYS = ("agents", "goals", "events")
STRING_FIELDS = frozenset({
    ("run", "name"), ("run", "mode"), ("agents", "id"), ("agents", "program"),
    ("agents", "mechanism"), ("goals", "agent"), ("goals", "goal"), ("goals", "op"),
    ("goals", "goal_id"), ("events", "kind")})
"""(table, field) of the fields that take a string: a value given to one stays text."""
_PART = re.compile(r"[A-Za-z0-9_-]+")


class OverrideError(WorldError):
    """A `--set` that is not KEY=VALUE, or whose key or value cannot be read."""


@dataclass(frozen=True, eq=False)
class Override:
    """One `--set KEY=VALUE`: ``text`` as given (stripped), ``key`` its parts, ``value`` the
    value it sets (module doc)."""

    text: str
    key: tuple[str, ...]
    value: Any

    @property
    def label(self) -> str:
        """How messages name it: `--set run.cycles=300`."""
        return f"--set {self.text}"


def parse_override(text: str) -> Override:
    """``text`` (KEY=VALUE) as an Override; raises OverrideError saying what is wrong (its
    message starts `--set TEXT: `)."""
    text = text.strip()
    name, eq, raw = text.partition("=")
    key = tuple(p.strip() for p in name.split("."))
    label = f"--set {text}"
    if not eq or not name.strip():
        raise OverrideError(f"{label}: expected KEY=VALUE, e.g. run.cycles=300 or "
                            "agents.ME.program=programs/x.tlp")
    bad = [p for p in key if not _PART.fullmatch(p)]
    if bad:
        raise OverrideError(f"{label}: {name.strip()!r} is not a key: expected names of "
                            "letters, digits, '_' or '-' joined by dots, e.g. world.pedestrians")
    if key[0] not in TABLES:
        raise OverrideError(f"{label}: unknown table {key[0]!r}; expected one of {list(TABLES)}")
    if len(key) < 2:
        raise OverrideError(f"{label}: name a field of [{key[0]}], e.g. {_example(key[0])}")
    try:
        value = toml_value(raw.strip(), label, key)
    except TomlTextError as exc:
        raise OverrideError(str(exc)) from None
    if value is NOT_A_VALUE or (_takes_string(key) and not isinstance(value, str)):
        value = raw.strip()
    return Override(text, key, _from_here(key, value))


def _from_here(key: tuple[str, ...], value: Any) -> Any:
    """A program path typed on the command line is read from the working directory, as
    every path a command takes: made absolute when the file is there (else it is looked up
    as the file's own would be, beside the scenario and above)."""
    if key[0] != "agents" or key[-1] != "program" or not isinstance(value, str):
        return value
    path = Path(value)
    try:
        return str(path.resolve()) if not path.is_absolute() and path.is_file() else value
    except (OSError, ValueError):  # too long to look up, a NUL byte: left to the check
        return value


def _example(table: str) -> str:
    return {"run": "run.cycles=300", "world": "world.pedestrians=20",
            "agents": "agents.ME.program=programs/x.tlp", "goals": "goals.1.priority=4",
            "events": "events.1.at_cycle=50"}[table]


def _takes_string(key: tuple[str, ...]) -> bool:
    """Whether the field ``key`` names is one of STRING_FIELDS (an array entry's field is
    the third part: agents.ME.program)."""
    field = key[2] if key[0] in ARRAYS and len(key) == 3 else key[1] if len(key) == 2 else ""
    return (key[0], field) in STRING_FIELDS


def apply_overrides(doc: dict[str, Any], overrides: tuple[Override, ...]
                    ) -> tuple[dict[str, Any], dict[Override, str]]:
    """A copy of the scenario document ``doc`` with ``overrides`` applied in order, and what
    is wrong with each that has no place in it (an agent id the file does not have): those
    are left out."""
    out = copy.deepcopy(doc)
    return out, {o: problem for o in overrides if (problem := _apply(out, o))}


def _apply(doc: dict[str, Any], o: Override) -> str:
    """Set ``o`` in ``doc``; "" when done, else what is wrong."""
    node: Any = doc
    for depth, part in enumerate(o.key[:-1]):
        place = ".".join(o.key[:depth + 1])
        if isinstance(node, dict):
            if part not in node:
                if depth == 0 and part in ARRAYS:
                    return f"{o.label}: the scenario has no [[{part}]] entries to change"
                node[part] = {}
            node = node[part]
        elif isinstance(node, list):
            index = _entry(node, part, o.key[0] == "world")
            if isinstance(index, str):
                return f"{o.label}: {index}"
            node = node[index]
        else:
            return f"{o.label}: {place} is {node!r:.40}, not a table or an array"
    last, value = o.key[-1], copy.deepcopy(o.value)  # a later override may change inside it
    if isinstance(node, dict):
        node[last] = value
    elif isinstance(node, list):
        index = _entry(node, last, o.key[0] == "world")
        if isinstance(index, str):
            return f"{o.label}: {index}"
        node[index] = value
    else:
        return f"{o.label}: {'.'.join(o.key[:-1])} is {node!r:.40}, not a table or an array"
    return ""


def _entry(entries: list[Any], name: str, by_agent: bool) -> int | str:
    """The index of the entry ``name`` names (module doc), or what is wrong as text."""
    tables = [(i, e) for i, e in enumerate(entries) if isinstance(e, dict)]
    for i, e in tables:
        if e.get("id") == name:
            return i
    if by_agent:
        agents = [i for i, e in tables if "id" not in e and e.get("agent") == name]
        if len(agents) == 1:
            return agents[0]
    if name.isdigit() and 1 <= int(name) <= len(entries):
        return int(name) - 1
    ids = [e["id"] for _, e in tables if isinstance(e.get("id"), str)]
    named = f"its id ({', '.join(ids)}) or " if ids else ""
    return (f"no entry {name!r}: name one by {named}its number (1..{len(entries)})"
            if entries else f"no entry {name!r}: the array is empty")
