"""A program swapped into a running agent's stages (`teleo program load`; docs/bus.md,
"Changing a running launch"). The world puts the program in the state of the cycle it is due
at, the agent's perception forwards it with the percepts of that cycle (Percepts.program),
and the inference and executive stages swap it in before they compute that cycle, so both
run the new program from the same cycle; each says what it did with its output of the cycle
(Beliefs.swap, Intention.swap: {"program", "ok", "reason", "dropped"}), which is what
`teleo program load` reports and what the record keeps.

With `--swapped FILE` (the launcher gives both stages the same file in the run folder) each
stage writes the program it swapped in there, and a stage that starts (a restart after a
crash) runs the program that file holds rather than its `--program`: a restart does not undo
a swap.

The program is read here exactly as `teleo check` reads a file (agents/lang; every error as
file:line:col); a program that does not read is refused by both stages alike (the same text,
the same reader) and the agent goes on with the one it ran. The engine state carries over by
agents/lang/swap.py's pure carry_state."""

from __future__ import annotations

import json
import logging
from pathlib import Path
from typing import Any

from agents.lang import Engine, ProgramError, load_program, load_program_text
from agents.processes.goal_sync import validator
from agents.processes.persist import write_atomically


def read_program(entry: dict[str, Any]) -> tuple[Any, str]:
    """(the Program of a Percepts.program entry, "") or (None, why not: every error)."""
    name = str(entry.get("name") or "<program>")
    try:
        return load_program_text(str(entry.get("text", "")), name), ""
    except ProgramError as exc:
        return None, "; ".join(str(d) for d in exc.errors) or str(exc)


def note(entry: dict[str, Any], reason: str = "", dropped: tuple[str, ...] = ()
         ) -> dict[str, Any]:
    """A stage's verdict on a swap, as Beliefs.swap and Intention.swap carry it."""
    return {"program": str(entry.get("name", "")), "ok": not reason, "reason": reason,
            "dropped": list(dropped)}


def said(process: str, cycle: int, verdict: dict[str, Any], log: logging.Logger) -> None:
    """The verdict in the process's log."""
    if verdict["ok"]:
        log.info("cycle %d: now running %s%s", cycle, verdict["program"],
                 f"; dropped: {'; '.join(verdict['dropped'])}" if verdict["dropped"] else "")
    else:
        log.warning("cycle %d: %s kept its program: %s", cycle, process, verdict["reason"])


def keep(path: str | None, entry: dict[str, Any], cycle: int, log: logging.Logger) -> None:
    """Write the program swapped in at `cycle` to `path` (nothing without one)."""
    if not path:
        return
    try:
        write_atomically(Path(path), json.dumps({"name": entry.get("name", ""),
                                                 "text": entry.get("text", ""),
                                                 "cycle": cycle}))
    except OSError as exc:   # a full disk: the swap holds, a restart would undo it
        log.error("the program swapped in at cycle %d was not kept in %s: %s", cycle, path,
                  exc)


def kept(path: str | None, program_path: str, log: logging.Logger) -> Any:
    """The program to start with: the one swapped in and kept in `path` when there is one
    that reads, else the file `program_path` (ProgramError when it does not read)."""
    if path and Path(path).exists():
        try:
            entry = json.loads(Path(path).read_text())
            program, why = read_program(entry)
        except (OSError, ValueError, AttributeError) as exc:
            program, why = None, str(exc)
        if program is not None:
            log.info("running %s, swapped in at cycle %s (kept in %s)", entry.get("name"),
                     entry.get("cycle"), path)
            return program
        log.error("the program kept in %s does not read (%s): running %s", path, why,
                  program_path)
    return load_program(program_path)


class ProgramWatch:
    """The goal-entry process's view of each agent's program (agents/processes/goals.py): an
    Engine to check a posted goal against and the program's own goals (the priority rule),
    both following the programs swapped in (WorldState.control), so a goal of the new program
    is taken and one it cannot pursue refused from the cycle of the swap on."""

    def __init__(self, scenario: Any) -> None:
        self.engines = {a.id: Engine(load_program(str(a.program))) for a in scenario.agents}
        self.standing = {a: _standing(e.program) for a, e in self.engines.items()}
        self.validate = validator(self.engines)

    def follow(self, control: dict[str, Any], log: logging.Logger) -> None:
        """Take the programs of a world state's ``control`` (one that does not read: kept)."""
        for agent, entry in (control.get("programs") or {}).items():
            program, why = read_program(entry) if isinstance(entry, dict) else (None, "")
            if agent in self.engines and program is not None:
                self.engines[agent] = Engine(program)
                self.standing[agent] = _standing(program)
                log.info("goals of %s now checked against %s", agent, entry.get("name"))
            elif why:
                log.warning("goals of %s: program %s not read: %s", agent, entry.get("name"),
                            why)


def _standing(program: Any) -> tuple[str, ...]:
    return tuple(str(g.literal) for g in program.goals)
