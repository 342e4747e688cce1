"""Which program each agent of the viewed run runs, for the beliefs panel (beliefs.py).

The candidates of an agent, tried in order: the program its scenario names (the scenario of a
record's `teleo.run` metadata, or of a live launch's registry entry), then each file a skill
of its decisions was written in (the `where` of a path step). The first that loads is used,
and checked against the run: inference with it on a cycle's recorded percepts must give the
recorded beliefs, else the panel says the program differs from the one the agent ran.
A program swapped in while the run ran (`teleo program load`: the percepts of the cycle it came
at carry its text) is the agent's from that cycle on, live, replayed or recorded alike.
"""

from __future__ import annotations

import logging
import threading
from pathlib import Path
from typing import Any

from agents.lang import Engine, LangError, Program, load_program, load_program_text

log = logging.getLogger(__name__)


class Programs:
    """Thread-safe: a feed adds candidates, server threads load and check (an Engine keeps
    what it inferred last, so the check runs one at a time)."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._checking = threading.Lock()            # one inference at a time per view
        self._candidates: dict[str, list[str]] = {}
        self._loaded: dict[str, Program | str] = {}  # path -> the program, or why it failed
        self._engines: dict[str, Engine] = {}        # path -> an engine for the check
        self._base = ""   # the launch's folder, where relative paths start ("": this one)
        self._swaps: dict[str, list[tuple[int, str]]] = {}  # agent -> (cycle, name), sorted

    def add(self, agent: str, path: str) -> None:
        """One more candidate program file for `agent` (ignored when already known); a
        relative path is taken from the launch's folder, as the launch read it."""
        if path and self._base:
            path = str(Path(self._base, path))
        with self._lock:
            known = self._candidates.setdefault(agent, [])
            if path and path not in known:
                known.append(path)

    def from_scenario(self, scenario: str, base: str = "") -> None:
        """The programs a scenario file gives its agents (nothing when it cannot be read);
        ``base``: the folder the launch ran in (the run registry's `cwd`), where the
        scenario's and its programs' relative paths start."""
        from world.errors import WorldError
        from world.run_scenario import load_scenario

        self._base = base
        scenario = str(Path(base, scenario)) if base and scenario else scenario
        try:
            agents = load_scenario(scenario).agents if scenario else ()
        except (WorldError, OSError) as exc:
            log.info("beliefs panel: scenario %s not read (%s)", scenario, exc)
            return
        for a in agents:
            self.add(a.id, str(a.program))

    def saw(self, agent: str, decision: dict[str, Any]) -> None:
        """The files a decision's skills were written in (`where` = file:line:col)."""
        if not isinstance(decision, dict):
            return
        paths = [decision.get("path"), *(p.get("path") for p in _dicts(decision.get("parallel")))]
        for step in (s for path in paths for s in _dicts(path)):
            where = str(step.get("where", ""))
            if where.count(":") >= 2:
                self.add(agent, where.rsplit(":", 2)[0])

    def swap(self, agent: str, cycle: int, entry: Any) -> None:
        """`agent` ran the program of ``entry`` ({"name", "text"}, Percepts.program) from
        `cycle` on."""
        if not isinstance(entry, dict) or not isinstance(entry.get("text"), str):
            return
        name = f"{entry.get('name', 'program')} (from cycle {cycle})"
        try:
            found: Program | str = load_program_text(entry["text"], str(entry.get("name")))
        except LangError as exc:
            found = str(exc).splitlines()[0]
        with self._lock:
            self._loaded[name] = found
            swaps = self._swaps.setdefault(agent, [])
            if (cycle, name) not in swaps:
                swaps.append((cycle, name))
                swaps.sort()

    def get(self, agent: str, cycle: int | None = None) -> tuple[Program | None, str]:
        """(the program of `agent` at `cycle` (None: the newest), its file), or (None, why
        there is none). A file is read once, outside the lock (a feed adding candidates
        meanwhile does not wait)."""
        with self._lock:
            ran = [name for c, name in self._swaps.get(agent, ())
                   if cycle is None or c <= cycle]
            candidates = ran[-1:] or list(self._candidates.get(agent, ()))
        tried = []
        for path in candidates:
            with self._lock:
                found = self._loaded.get(path)
            if found is None:
                found = _load(path)
                with self._lock:
                    found = self._loaded.setdefault(path, found)
            if isinstance(found, Program):
                return found, path
            tried.append(found)
        if not tried:
            return None, (f"no program known for {agent}: neither the run's scenario nor a "
                          "decision of this agent names a program file")
        return None, "; ".join(tried)

    def differs(self, path: str, program: Program, percepts: list, model: list,
                beliefs: list) -> str:
        """"" when `program` infers the recorded `beliefs` from the recorded `percepts` (and
        the agent's world `model`), else a sentence saying how they differ."""
        with self._checking:
            engine = self._engines.get(path)
            if engine is None:
                engine = self._engines[path] = Engine(program, solver=None)
            try:
                inferred = {tuple(b.to_list()) for b in engine.infer(percepts, model)}
            except LangError as exc:
                return f"{path}: the recorded percepts do not read: {exc}"
        recorded = {tuple(b) for b in beliefs}
        if inferred == recorded:
            return ""
        extra, lost = sorted(inferred - recorded, key=str), sorted(recorded - inferred, key=str)
        sample = ", ".join("(" + " ".join(map(str, b)) + ")" for b in (extra + lost)[:2])
        return (f"{path} infers other beliefs from this cycle's percepts than the agent had "
                f"({len(extra)} more, {len(lost)} fewer: {sample}): the file may have changed "
                "since the run; the reasons below read the recorded beliefs")


def _dicts(items: Any) -> list[dict]:
    """The maps of a list (a record is only shape-checked: anything else is skipped)."""
    return [i for i in items if isinstance(i, dict)] if isinstance(items, list) else []


def _load(path: str) -> Program | str:
    try:
        return load_program(path)
    except LangError as exc:  # a file that cannot be read names itself (ProgramError)
        return str(exc).splitlines()[0]
