"""What the executive process keeps on disk so a restart loses nothing (the goal
stack, SCS threads, discount factors, learned skills and plans all live in EngineState,
serialisable, so a restarted executive loses none of them): the engine state as JSON, and the
learned skills in program syntax (agents/lang/solving/learned.py).

The state is written only when a cycle's decision changed it (its cycle number aside,
``same_but_cycle``): deciding a cycle again from the last state written then gives the
decision made the first time, since a decision is a function of the state and the cycle's
inputs (the engine's promise: every result is what a fresh Engine would give). So a restarted
executive the clock sends a cycle after the last one written decides it as it was decided, and
one it sends the last one written re-emits that cycle's outputs (``Saved``): a killed executive
loses nothing whichever cycle it dies in. A state that changes is written most cycles, so it goes
to a file kept open, in one ``pwrite`` system
call at offset 0 (padded with spaces, which JSON ignores, to the length of the longest version
so far): a process killed by a signal either made that call or did not, so the file holds one
whole version (creating a file costs milliseconds here, the write microseconds; this is not
a guard against power loss). The learned file changes rarely and is replaced by a rename.

A file that cannot be read back (not UTF-8, not JSON, the wrong shape) is never a crash: it is
set aside, kept under the first free name ``<name>.bad`` or ``<name>.bad-<n>`` (the run's
summary lists it, tools/records/summary_agents.py), and the executive starts afresh from the
skills still on disk (``read_back_learned``): a restart never loses a learned skill."""

from __future__ import annotations

import json
import logging
import os
import re
from dataclasses import dataclass, fields
from functools import cache
from operator import attrgetter
from pathlib import Path
from typing import Any

import orjson


def write_atomically(path: Path, text: str) -> None:
    """Replace ``path`` by ``text`` in one rename (same folder, so the same file system)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text, encoding="utf-8")
        os.replace(tmp, path)
    except OSError:
        tmp.unlink(missing_ok=True)  # a half-written copy would only take room
        raise


def set_aside(path: Path) -> Path:
    """Rename an unreadable ``path`` to the first free ``<name>.bad`` / ``<name>.bad-<n>``
    (an earlier one is never overwritten) and return the new path."""
    aside, n = path.with_name(f"{path.name}.bad"), 1
    while aside.exists():
        n += 1
        aside = path.with_name(f"{path.name}.bad-{n}")
    os.replace(path, aside)
    return aside


def set_aside_files(folder: Path) -> list[Path]:
    """The files of ``folder`` that were set aside as unreadable (``set_aside``), by name."""
    return sorted(p for p in folder.glob("*.bad*") if re.search(r"\.bad(-\d+)?$", p.name))


def same_but_cycle(a: Any, b: Any) -> bool:
    """Whether two engine states differ in their cycle number at most (a field-by-field
    comparison: the fields of a state left as it was are the same objects)."""
    return type(a) is type(b) and _kept(type(a))(a) == _kept(type(b))(b)


@cache
def _kept(kind: type) -> attrgetter:
    return attrgetter(*(f.name for f in fields(kind) if f.name != "cycle"))


@dataclass(frozen=True)
class Saved:
    """What the executive wrote after deciding bus cycle ``cycle``: the engine state for the
    next cycle, and the intention (Decision.to_dict()) and actions it published for this one,
    so that a restarted executive the clock sends ``cycle`` again re-emits them instead of
    deciding twice (a decision is not idempotent: it advances the state)."""

    cycle: int
    state: Any
    intention: dict[str, Any]
    actions: list[list[Any]]


class StateFile:
    """An executive's state file: ``load`` at start (None when there is none), ``save`` after
    a decision that changed the state, before its outputs are published (``changed`` says
    whether one did)."""

    def __init__(self, path: str | Path, log: logging.Logger) -> None:
        self.path = Path(path)
        self.log = log
        self.fd: int | None = None
        self.size = 0
        self.unsaved: int | None = None  # the first cycle whose save failed, until one works
        self.written: Any = None         # the engine state last written or read back

    def load(self) -> Saved | None:
        """What was last written, or None (no file yet, or one that cannot be read, whatever
        its bytes: then it is set aside (``set_aside``) and the run starts afresh, logged,
        never a crash)."""
        from agents.lang import EngineState, LangError

        try:
            data = self.path.read_bytes()
        except FileNotFoundError:
            return None
        except OSError as exc:   # a folder in its place, no permission: set aside below
            data, problem = b"", exc.strerror or str(exc)
        else:
            problem = ""
        try:
            if problem:
                raise ValueError(problem)
            doc = json.loads(data.decode("utf-8"))   # UnicodeDecodeError is a ValueError
            saved = Saved(int(doc["cycle"]), EngineState.from_dict(doc["state"]),
                          dict(doc["intention"]), list(doc["actions"]))
        except (ValueError, KeyError, TypeError, LangError) as exc:
            bad = set_aside(self.path)
            self.log.error("engine state %s: cannot be read (%s); kept as %s, starting afresh",
                           self.path, str(exc)[:300], bad)
            return None
        state = self.written = saved.state
        self.log.info("engine state %s read back (bus cycle %d): %d goal(s), %d goal stack(s), "
                      "%d learned skill(s)", self.path, saved.cycle, len(state.goals),
                      len(state.solver.stacks), len(state.learned))
        return saved

    def save(self, saved: Saved) -> None:
        """Write `saved`; one that cannot be written (a full disk) is logged, once until a
        save succeeds again, and the process goes on: the file keeps the last version that
        was written, from which a restart would decide the cycles after it again."""
        data = orjson.dumps({"cycle": saved.cycle, "state": saved.state.to_dict(),
                             "intention": saved.intention, "actions": saved.actions},
                            option=orjson.OPT_NON_STR_KEYS)  # ~10x json.dumps
        try:
            if self.fd is None:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
                self.size = os.fstat(self.fd).st_size
            os.pwrite(self.fd, data + b" " * (self.size - len(data)), 0)
        except OSError as exc:
            if self.unsaved is None:
                self.unsaved = saved.cycle
                self.log.error("engine state %s: cycle %d cannot be saved (%s); it keeps an "
                               "earlier cycle's", self.path, saved.cycle, exc.strerror or exc)
            return
        self.size = max(self.size, len(data))
        self.unsaved, self.written = None, saved.state

    def changed(self, state: Any) -> bool:
        """Whether ``state`` differs from the one on file by more than its cycle number (a
        state never written, or whose writing failed, has changed)."""
        return self.written is None or not same_but_cycle(state, self.written)


def read_back_learned(program: Any, path: Path, log: logging.Logger) -> tuple[str, ...] | None:
    """The skills of an agent's own learned file ``path`` (the one it writes) as a restart
    finds it: None when there is none; one that cannot be read is set aside (``set_aside``),
    logged, and None. ``program`` is the loaded Program the skills extend."""
    from agents.lang import LangError
    from agents.lang.loader import read_text
    from agents.lang.registry import read_learned

    if not path.is_file():
        return None
    try:
        return read_learned(program, read_text(path), str(path))
    except LangError as exc:
        bad = set_aside(path)
        log.error("learned skills %s: cannot be read (%s); kept as %s", path,
                  str(exc)[:300], bad)
        return None


class LearnedFile:
    """The learned-skills file of one agent, rewritten whenever a skill is learned."""

    def __init__(self, path: str | Path, program: str) -> None:
        self.path = Path(path)
        self.program = program
        self.written: tuple[str, ...] | None = None

    def save(self, learned: tuple[str, ...]) -> None:
        from agents.lang.registry import learned_text

        if learned != self.written:
            try:
                write_atomically(self.path, learned_text(learned, self.program))
            except OSError as exc:  # a full disk: tried again when the next skill is learned
                logging.getLogger(__name__).error("learned skills %s: not written (%s)",
                                                  self.path, exc.strerror or exc)
                return
            self.written = learned
