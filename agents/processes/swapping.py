"""A program swapped into a running agent's stages (`teleo program load`; docs/bus.md,
"Changing a running launch"). The world puts the program in the state of the cycle it is due
at, the agent's perception forwards it with the percepts of that cycle (Percepts.program),
and the inference and executive stages swap it in before they compute that cycle, so both
run the new program from the same cycle; each says what it did with its output of the cycle
(Beliefs.swap, Intention.swap: {"program", "ok", "reason", "dropped"}), which is what
`teleo program load` reports and what the record keeps.

The program is read here exactly as `teleo check` reads a file (agents/lang; every error as
file:line:col); a program that does not read is refused by both stages alike (the same text,
the same reader) and the agent goes on with the one it ran. The engine state carries over by
agents/lang/swap.py's pure carry_state."""

from __future__ import annotations

import logging
from typing import Any


def read_program(entry: dict[str, Any]) -> tuple[Any, str]:
    """(the Program of a Percepts.program entry, "") or (None, why not: every error)."""
    from agents.lang import ProgramError, load_program_text

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
