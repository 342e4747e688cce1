"""The worlds teleo can run, found as Python entry points of the group ``teleo.worlds``.

A world package (teleo's own three included: pyproject.toml `[project.entry-points."teleo.worlds"]`)
names its Domain in its own pyproject.toml:

    [project.entry-points."teleo.worlds"]
    pucks = "teleo_world_pucks:DOMAIN"

Names are read from the installed packages' metadata (importlib.metadata, as pytest finds its
plug-ins and Gymnasium its environments); a world's module is imported only when the world is
first used, so a process that runs one world never imports the others' physics. A world whose
import fails (an ImportError, any other exception, or an object that is not a Domain) is kept
with a one-line reason: it never stops teleo from listing or running the others.

When teleo runs from a source checkout whose installed metadata is older than its
pyproject.toml (a world added to the table since the last `pip install -e .`), the names of
that table are taken too, so a merge that adds a world needs no reinstall to be seen.
"""

from __future__ import annotations

import difflib
import importlib
import tomllib
from dataclasses import dataclass
from functools import cache
from importlib import metadata
from pathlib import Path
from typing import Any

from world.errors import ConfigError

GROUP = "teleo.worlds"
"""The entry-point group a world package registers its Domain under."""


@dataclass(frozen=True)
class Entry:
    """One registered world: ``target`` is "package.module:ATTRIBUTE" naming a Domain."""

    name: str
    target: str
    dist: str      # the distribution (package) that provides it, "" when unknown
    version: str


@dataclass(frozen=True)
class Found:
    """A registered world as `teleo worlds` shows it: its summary, or why it failed."""

    entry: Entry
    summary: str = ""
    error: str = ""       # one line, no traceback; "" when the world loaded


CHECKOUT = Path(__file__).resolve().parent.parent / "pyproject.toml"
"""teleo's pyproject.toml when teleo runs from a checkout (absent beside an installed wheel)."""


def source_entries(path: Path = CHECKOUT) -> list[Entry]:
    """The `teleo.worlds` table of teleo's own pyproject.toml at ``path`` (none when there is
    no such file, or it is another project's)."""
    try:
        project = tomllib.loads(path.read_text(encoding="utf-8")).get("project", {})
    except (OSError, tomllib.TOMLDecodeError, UnicodeDecodeError):
        return []
    if project.get("name") != "teleo":
        return []
    table = project.get("entry-points", {}).get(GROUP, {})
    return [Entry(name, target, "teleo", str(project.get("version", "")))
            for name, target in table.items() if isinstance(target, str)]


@cache
def entries() -> dict[str, Entry]:
    """Every registered world by name, installed packages first, then teleo's own checkout
    table for names the installed metadata lacks. A name two packages claim goes to the first
    found (sys.path order); the other is listed by `conflicts`."""
    found: dict[str, Entry] = {}
    for ep in metadata.entry_points(group=GROUP):
        dist = ep.dist.metadata["Name"] if ep.dist is not None else ""
        version = ep.dist.version if ep.dist is not None else ""
        entry = Entry(ep.name, ep.value, dist or "", version or "")
        if ep.name in found:
            if found[ep.name].dist != entry.dist:
                _conflicts.append(entry)
            continue
        found[ep.name] = entry
    for entry in source_entries():
        found.setdefault(entry.name, entry)
    return found


_conflicts: list[Entry] = []


def conflicts() -> tuple[Entry, ...]:
    """Entries whose name another package registered first (shown by `teleo worlds`)."""
    entries()
    return tuple(_conflicts)


def names() -> tuple[str, ...]:
    """The registered worlds' names, teleo's own first, then the others, each alphabetically
    (so lists and parametrised tests have the same order wherever they run)."""
    found = entries()
    own = sorted(e.name for e in found.values() if e.dist == "teleo")
    return tuple(own + sorted(n for n in found if n not in own))


def unknown(name: object, key: str = "[world] domain") -> str:
    """The one-line refusal of a world name nobody registered: the near ones, then all."""
    known = names()
    near = difflib.get_close_matches(str(name), known, n=3, cutoff=0.6)
    hint = f"; did you mean {' or '.join(repr(n) for n in near)}?" if near else ""
    return (f"{key}: unknown domain {name!r}{hint} known: {', '.join(known) or 'none'} "
            f"(`teleo worlds` lists them and any that failed to load)")


def _why(exc: BaseException) -> str:
    """An exception as one line: its type and the first line of its message."""
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0]}" if text else type(exc).__name__


def _import(entry: Entry) -> Any:
    """The object ``entry.target`` names ("module" or "module:attr.attr")."""
    module, _, attrs = entry.target.partition(":")
    obj: Any = importlib.import_module(module.strip())
    for attr in filter(None, attrs.strip().split(".")):
        obj = getattr(obj, attr)
    return obj


@cache
def _load(name: str, kind: type) -> tuple[Any, str]:
    """(the Domain, "") or (None, why it failed: one line). Cached: a world is imported once.
    ``kind`` is world.domain.Domain (passed in: world.domain imports this module)."""
    entry = entries()[name]
    try:
        obj = _import(entry)
    except (Exception, SystemExit) as exc:  # a plug-in's failure is any exception: kept, shown
        return None, f"import of {entry.target} failed: {_why(exc)}"
    if not isinstance(obj, kind):
        return None, (f"{entry.target} is a {type(obj).__name__}, not a world.domain.Domain")
    if obj.name != name:
        return None, f"{entry.target} is the Domain {obj.name!r}, registered as {name!r}"
    return obj, ""


def load(name: str, kind: type, key: str = "[world] domain") -> Any:
    """The Domain (an instance of ``kind``) registered as ``name``; raises ConfigError (one
    line) for a name nobody registered or a world that failed to load."""
    if name not in entries():
        raise ConfigError(unknown(name, key))
    domain, why = _load(name, kind)
    if domain is None:
        entry = entries()[name]
        raise ConfigError(f"{key}: world {name!r} ({_provider(entry)}) failed to load: {why}")
    return domain


def _provider(entry: Entry) -> str:
    return f"{entry.dist} {entry.version}".strip() or "unknown package"


def survey(kind: type) -> list[Found]:
    """Every registered world, each loaded now (an instance of ``kind``, world.domain.Domain):
    its summary, or why it failed."""
    rows = []
    for name in names():
        domain, why = _load(name, kind)
        rows.append(Found(entries()[name], domain.summary if domain else "", why))
    rows += [Found(e, "", f"name already registered by {_provider(entries()[e.name])}")
             for e in conflicts()]
    return rows


def forget() -> None:
    """Read the entry points again on next use (a package installed or removed meanwhile:
    tests, a long-lived tool); a world already imported stays imported."""
    entries.cache_clear()
    _load.cache_clear()
    _conflicts.clear()
