"""The specs the bus message kinds are declared with (bus/messages.py: each field's spec in
its metadata, bus/kinds.py), checked by `bus.codec.decode` before any process sees the message
(docs/bus.md, "What a reader checks").

A field whose inside is another package's (a snapshot is its world's, a memory's SCS state
the engine's, an intention the engine's Decision) is checked here as plain data only (no
bytes, NaN or infinity, string keys, bounded depth: what every reader and writer of it relies
on; schema.Plain), and by its owner when read: the world's snapshot
(world/<domain>/snapshot.py SNAPSHOT) in perception, the SCS state by the engine
(agents/lang/scs/state.py, fitting.py), an intention's goals by the goal-entry process
(agents/processes/goal_store.py DECISION). Rows of neutral lists (percepts, beliefs, actions,
world-model facts) are checked by bus/rows.py in C-level passes (the hot path).
"""

from __future__ import annotations

import sys
from typing import Any

from bus.rows import check_rows
from bus.schema import (
    INT64,
    Atom,
    Bool,
    FieldError,
    Int,
    ListOf,
    MapOf,
    Num,
    OneOf,
    Plain,
    Record,
    Spec,
    Str,
    TupleOf,
)

MEMORY_DEPTH = 128
"""[levels] of an agent's memory or an intention: an SCS body nests a frame per construct
(programs nest at most 64 levels, docs/language.md "Limits")."""
UNBOUNDED = sys.maxsize  # a string whose length its reader bounds with its own message


class Rows(Spec):
    """Rows of neutral lists: bus/rows.py's check, its TypeError seen as a FieldError."""

    expected = "arrays of str, int or float"

    def check(self, value: Any) -> Any:
        try:
            return check_rows(value)
        except TypeError as exc:
            raise FieldError(str(exc)) from None


class All(Spec):
    """Every spec in turn (plain data first, then the shape its readers rely on)."""

    def __init__(self, *specs: Spec) -> None:
        self.specs = specs
        self.expected = specs[-1].expected

    def check(self, value: Any) -> Any:
        for spec in self.specs:
            spec.check(value)
        return value


class Tuple(Spec):
    """An array, received as a tuple (the dataclasses' own form of a repeated field)."""

    def __init__(self, spec: Spec) -> None:
        self.spec, self.expected = spec, spec.expected

    def check(self, value: Any) -> Any:
        return tuple(self.spec.check(value))


OUTCOME = Record({"action": ListOf(Atom(), min_len=1, what="[name, arg, ...]"),
                  "status": OneOf(("done", "failed")), "reason": Str(max_len=UNBOUNDED)},
                 open=True, what="an outcome {action, status, reason}")
"""An action's outcome as the world reports it (docs/architecture.md, "Neutral data forms")."""
OUTCOMES = All(Plain(16, top=list), ListOf(OUTCOME))
_MEMORY_SHAPE = Record({}, {"model": Rows(), "scs": Record({}, open=True)}, open=True,
                       what="an agent memory {model, scs}")
MEMORY = All(Plain(MEMORY_DEPTH), _MEMORY_SHAPE)
"""An agent's memory (docs/bus.md, "Agent memory"): an open map of plain data (the world
writes each change of it to its trace); its world-model facts are rows [pred, arg, ...], its
SCS state is the engine's to read (agents/lang/scs/state.py and fitting.py refuse a bad
index, a fact of the wrong arity)."""
GOAL_ENTRY = Record({"id": Str(max_len=32, min_len=1, what="a goal id"),
                     "goal": Str(max_len=UNBOUNDED), "priority": Int(),
                     "status": Str()}, open=True, what="a goal {id, goal, priority, status}")
"""One goal of an agent's GoalList (agents/processes/goal_store.py, GoalRecord.brief)."""
NAME = Str(what="a name")
PROGRAM = Record({}, {"name": Str(max_len=UNBOUNDED), "text": Str(max_len=UNBOUNDED)},
                 open=True, what="a program {name, text}")
"""A program sent to an agent's stages (`teleo program load`): its file name and text, read
and checked by the stages (agents/lang, every error as file:line:col)."""
SWAP = Record({}, {"program": Str(max_len=UNBOUNDED), "ok": Bool(),
                   "reason": Str(max_len=UNBOUNDED), "dropped": ListOf(Str(max_len=UNBOUNDED))},
              open=True, what="a swap {program, ok, reason, dropped}")
"""A stage's verdict on a program swapped in at this cycle (docs/bus.md, "Changing a running
launch")."""
MAP = Record({}, open=True)   # a map, its inside checked by its reader
STATS = MapOf(TupleOf(Num(0.0, as_float=True), Int(0)), key=NAME, max_len=256,
              what="stage stats {process: [compute_ms, late]}")
"""The stats an output carries (docs/bus.md, "Stage stats"): its stage's and those its inputs
carried, all of the message's cycle; process -> [compute_ms, late] (ProcessStats' fields)."""
TEXT = Str(max_len=UNBOUNDED, what="a string")

ENVELOPE = Record({"v": Int(), "run": TEXT, "cycle": Int(-1, INT64[1], what="a cycle"),
                   "sender": TEXT, "sent_ns": Int()}, open=True, what="an envelope")
