"""The registry: the one module outside the mechanism packages that imports them.

A mechanism (agents/lang/core/mechanism.py) is registered by one line in ``MECHANISMS``; the kernel
iterates over the mechanisms it is handed and never names one. Layering (docs/architecture.md,
"Dependency rule"): kernel rooms < mechanism packages < this registry < the assembly
(agents/lang/engine.py, agents/lang/loader.py) < agents/processes, tools.

Order matters where it shows: the mechanisms' state slots appear in the state file in this
order ("solver", "scs", "planner"), and their program sections after the kernel's.

Processes and tools that need something mechanism-specific (the learned-skills file, the agent
memory) ask here, not the mechanism package."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import replace
from typing import Any

from .core.mechanism import Mechanism, slot_kinds
from .execution.state import EngineState, use_slots
from .planning.mechanism import Planning
from .scs.mechanism import Scs
from .solving.bindings import instances_warning, never_true
from .solving.learned import (
    clause_heads,
    is_learned_text,
    learned_text,
    program_named,
    read_learned,
)
from .solving.mechanism import Solving

MECHANISMS: tuple[Mechanism, ...] = (Solving(), Scs(), Planning())
"""The shipped mechanisms: seed 000's means-ends solver, seed 002's SCS bodies, seed 003's
ROGUE planner. A fourth is one package plus one entry here."""

use_slots(slot_kinds(MECHANISMS))

__all__ = ["MECHANISMS", "Mechanism", "clause_heads", "handlers", "is_learned_text",
           "learned_text", "memory_of", "program_named", "read_learned", "remember"]
__all__ += ["instances_warning", "never_true"]   # a goal's impossible instances


def handlers(mechanisms: Iterable[Mechanism] = MECHANISMS) -> dict[str, type]:
    """Impasse handler name -> factory, over ``mechanisms`` in order."""
    out: dict[str, type] = {}
    for m in mechanisms:
        out.update(m.impasse_handlers())
    return out


def memory_of(state: EngineState, mechanisms: Iterable[Mechanism] = MECHANISMS
              ) -> dict[str, Any]:
    """The agent memory an executive sends out with its actions (docs/bus.md, "Agent
    memory"): every mechanism's part ({} when none has anything to keep). The learned-skills
file is the means-ends learner's (``learned_text``, ``read_learned``, re-exported here)."""
    out: dict[str, Any] = {}
    for m in mechanisms:
        out.update(m.memory(state))
    return out


def remember(state: EngineState, memory: dict[str, Any], program: Any,
             mechanisms: Iterable[Mechanism] = MECHANISMS) -> EngineState:
    """``state`` with the slots read back from a memory the world handed back; raises
    LangError (StateError) when the memory does not fit ``program``."""
    changes = {}
    for m in mechanisms:
        value = m.remember(memory, program)
        if value is not None and m.slot:
            changes[m.slot] = value
    return replace(state, **changes) if changes else state
