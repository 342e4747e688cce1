"""The stats of a message, whichever way they travel (docs/bus.md, "Stage stats").

A stage carries its per-cycle figures (ProcessStats' compute_ms and late) in its output, in the
``stats`` field of Percepts, Beliefs, Actions and GoalList (the goal entry's), together with
those its inputs carried: an agent's Actions hold every stage of its pipeline, the goal
entry's included, all of the message's cycle. A ProcessStats of its own is still sent by a
process with no such output (the world, the recorder), by a stage, the goal entry or a shared
process idle a while after a cycle (bus/stage.py), and is what older records hold. Readers
take both through these two functions:

    for s in stats_of(msg):          # ProcessStats objects, one per process
        seen[s.process] = s.env.cycle
    for process, cycle, ms, late in record_stats(wire_map):   # a record's or the view's map
        ...
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from bus.messages import Envelope, Message, ProcessStats

STATS_FIELD = "stats"


def figures_of(msg: Message) -> Iterator[tuple[str, float, int]]:
    """(process, compute_ms, late) of every stats in `msg`, as `stats_of` finds them, without
    a ProcessStats made for each (the clock reads those of every Actions it waits for)."""
    if isinstance(msg, ProcessStats):
        yield msg.process, msg.compute_ms, msg.late
        return
    for process, (ms, late) in (getattr(msg, STATS_FIELD, None) or {}).items():
        yield process, float(ms), int(late)


def stats_of(msg: Message, own: bool = False) -> tuple[ProcessStats, ...]:
    """The ProcessStats in `msg`: itself if it is one, else one per process whose stats it
    carries (none for a kind without them); `own`: only its sender's (a reader that sees
    every output, and would count the stats carried on from the inputs twice)."""
    if isinstance(msg, ProcessStats):
        return (msg,)
    carried = getattr(msg, STATS_FIELD, None)
    if not carried:
        return ()
    env = msg.env
    return tuple(ProcessStats(Envelope(env.v, env.run, env.cycle, process, env.sent_ns),
                              process, float(ms), int(late))
                 for process, (ms, late) in carried.items()
                 if not own or process == env.sender)


def record_stats(record: Mapping[str, Any], own: bool = False
                 ) -> Iterator[tuple[str, int, float, int]]:
    """(process, cycle, compute_ms, late) of every stats a wire map (a record's line, the
    view's feed) holds, as `stats_of` does for a message."""
    env = record.get("env") or {}
    cycle = env.get("cycle", -1)
    if record.get("kind") == "ProcessStats":
        yield record["process"], cycle, float(record["compute_ms"]), int(record["late"])
        return
    carried = record.get(STATS_FIELD)
    if not isinstance(carried, Mapping):
        return
    for process, figures in carried.items():
        if own and process != env.get("sender"):
            continue
        ms, late = figures
        yield process, cycle, float(ms), int(late)
