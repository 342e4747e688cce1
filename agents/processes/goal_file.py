"""The goal store on disk: durable saves, the last good copy, and recovery from a damaged file.

A save writes the store to `goals.json` and then the same text to `goals.json.bak`, each by
temp file, fsync, rename and fsync of the folder, so a crash or power loss at any moment
leaves at least one complete, current copy. `open_store` reads `goals.json`; when it is
damaged (truncated, empty, not JSON, JSON of the wrong shape, a bad status) it moves it aside
to `goals.json.damaged-<n>`, recovers from the copy, and says what it found and did. When
nothing can be recovered it says so (`Opened.lost`); the goals process logs it as an error
and the run's summary shows it (the store's `incidents`).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path

from agents.lang import ProgramError
from agents.lang.core.limits import MAX_STATE_STRING, read_json
from agents.processes.goal_store import GoalStore, GoalStoreError

BACKUP_SUFFIX = ".bak"
LOST = "GOALS LOST: "
"""How an incident in which nothing could be recovered begins (the summary looks for it)."""
MAX_STORE_BYTES = 16 * 1024 * 1024
"""[bytes] of a store file; a bounded store (goal_store.py limits) is far smaller."""


@dataclass(frozen=True)
class Opened:
    """The store to run with and what recovery did: `incident` is "" for a good or absent
    file; `lost` is True when a damaged store could not be recovered at all."""

    store: GoalStore
    incident: str = ""
    lost: bool = False


def backup_path(path: Path) -> Path:
    return path.with_name(path.name + BACKUP_SUFFIX)


def save(store: GoalStore, path: Path) -> None:
    """Write `store` durably to `path` and then to its last good copy (raises OSError)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(store.to_json(), indent=1)
    _write_durably(path, text)
    _write_durably(backup_path(path), text)


def read_store(path: Path) -> GoalStore:
    """The store saved in `path`; raises GoalStoreError saying what is wrong with it."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_STORE_BYTES + 1)
    except OSError as exc:
        raise GoalStoreError(f"cannot read it: {exc.strerror}") from None
    if len(data) > MAX_STORE_BYTES:
        raise GoalStoreError(f"larger than {MAX_STORE_BYTES} bytes")
    if not data.strip():
        raise GoalStoreError("the file is empty" if not data else "the file holds only blanks")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise GoalStoreError(f"not UTF-8 text (byte 0x{data[exc.start]:02x} at offset "
                             f"{exc.start})") from None
    try:
        doc = read_json(text, str(path), MAX_STORE_BYTES, max_string=MAX_STATE_STRING)  # notes
    except ProgramError as exc:
        where = exc.diagnostics[0]
        raise GoalStoreError(f"not valid JSON at {where.line}:{where.col}: {where.message}") \
            from None
    return GoalStore.from_json(doc)


def open_store(path: Path) -> Opened:
    """The store of `path`, recovered from its last good copy when damaged (see module doc).
    Never raises for a damaged file; a recovered store is saved again at once."""
    backup = backup_path(path)
    if not path.exists() and not backup.exists():
        return Opened(GoalStore())  # a new run
    if path.exists():
        try:
            return Opened(read_store(path))
        except GoalStoreError as exc:
            problem = str(exc)
        damaged = f"goal store {path}: {problem}; moved aside to {_move_aside(path)}"
    else:
        damaged = f"goal store {path}: missing although its copy {backup.name} exists"
    try:
        store = read_store(backup)
        users = len(store.goals)
        outcome = f"recovered {users} goal(s) from {backup}"
        lost = False
    except GoalStoreError as exc:
        store = GoalStore()
        aside = f"; moved aside to {_move_aside(backup)}" if backup.exists() else ""
        outcome = (f"its last good copy {backup}: {exc}{aside}; NOTHING RECOVERED: the goals "
                   "users posted are lost (the scenario's scripted goals are posted again)")
        lost = True
    incident = f"{LOST if lost else ''}{damaged}; {outcome}"
    store = store.noted(incident)
    try:
        save(store, path)
    except OSError as exc:
        incident += f"; the recovered store cannot be saved: {exc}"
    return Opened(store, incident, lost)


def _move_aside(path: Path) -> str:
    """Rename a damaged `path` to the first free `<name>.damaged-<n>`; returns the new name
    (or why it could not be moved)."""
    n = 1
    while path.with_name(f"{path.name}.damaged-{n}").exists():
        n += 1
    aside = path.with_name(f"{path.name}.damaged-{n}")
    try:
        os.replace(path, aside)
        _fsync_dir(path.parent)
    except OSError as exc:
        return f"(nowhere: {exc.strerror})"
    return aside.name


def _write_durably(path: Path, text: str) -> None:
    """Temp file, fsync, rename over `path`, fsync of the folder (so the rename is kept too)."""
    tmp = path.with_name(path.name + ".tmp")
    try:
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError:
        tmp.unlink(missing_ok=True)  # a full disk: the old copy stays, the room comes back
        raise
    _fsync_dir(path.parent)


def _fsync_dir(folder: Path) -> None:
    fd = os.open(folder, os.O_RDONLY | os.O_DIRECTORY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
