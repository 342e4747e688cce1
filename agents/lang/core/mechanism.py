"""The Mechanism protocol: what a mechanism (the means-ends solver, SCS bodies, the ROGUE
planner, or a fourth) contributes to the kernel, so that the kernel never names one
(as pyperplan wires its searches from registries, and py_trees ticks any behaviour
through one interface).

A mechanism is a frozen value whose hooks the kernel calls in registry order
(agents/lang/registry.py holds the shipped ones); every hook has a default that contributes
nothing, so a mechanism overrides only what it needs:

- reading a program: ``sections`` (its own program sections, name -> handler(parser, node),
  the handler adding what it read to ``parts.sections``) and, for the one mechanism that
  reads a skill's ``:body``, ``read_body`` / ``body_checks`` / ``body_actions``;
- checking: ``asserted`` (facts its skills assert, defined as predicates before the checks);
- its state: ``slot`` (the EngineState key, also its key in the state file) and
  ``state_type`` (a frozen class with ``to_dict``/``from_dict`` whose ``()`` is the empty
  state);
- running: ``runners`` (Skill.kind -> body runner, agents/lang/execution/paths.py BodyRunner),
  ``impasse_handlers`` (name -> factory of an ImpasseHandler, agents/lang/execution/executive.py),
  ``facts`` (base facts it adds to inference), ``model_reader`` (reads a world model handed
  to Engine.infer), ``intention`` (its part of what decides the next action, for the loop
  watch, agents/lang/execution/loops.py);
- the executive process: ``memory`` / ``remember`` (what goes out with the actions and comes
  back with the world state, docs/bus.md "Agent memory"); ``carry`` (its state under a new
  program, `teleo program load`: agents/lang/swap.py).

Its part of the run summary is not a hook: the summaries are the tools' (a Report in
tools/records/mechanism_reports.py).

Its part of the decision and the explanation is a Section (agents/lang/core/explanation.py) that
its runner or handler appends to ``walk.sections``; ``teleo step --json`` shows a decision's
sections and the state's slots by key.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from .errors import LangError


@dataclass(frozen=True)
class SkillMap:
    """How the skills of an old program relate to a new one's (`teleo program load`): each
    old skill number that is in the new program unchanged (the same clause, wherever it is
    written) -> its new number, and likewise its name (``at-address#2``)."""

    numbers: Mapping[int, int] = field(default_factory=dict)
    names: Mapping[str, str] = field(default_factory=dict)


class Mechanism:
    """Base of every mechanism: hooks that contribute nothing (override what you need).

    Subclasses are frozen dataclasses (or plain classes without state): one instance serves
    every agent, everything kept between cycles lives in the state slot."""

    name: str = ""
    slot: str = ""             # EngineState key of its state ("" for none)
    state_type: type | None = None

    # -- reading ---------------------------------------------------------------------------
    def sections(self) -> dict[str, Callable[[Any, Any], None]]:
        """Program section name -> handler(parser, node)."""
        return {}

    def reads_body(self) -> bool:
        """True for the mechanism that reads a skill's ``:body``."""
        return False

    def read_body(self, parser: Any, node: Any) -> Any:
        """The step tree of a ``:body`` node (None after reporting through ``parser.err``)."""
        raise LangError(f"mechanism {self.name} reads no :body")

    def body_checks(self, checker: Any, skills: list, resources: dict | None) -> Any:
        """An object whose ``check(skill, bound)`` reports a body's problems."""
        return None

    def body_actions(self, body: Any) -> Iterable:
        """The ActionTemplates a body can send (Program.actions)."""
        return ()

    def program_actions(self, program: Any) -> Iterable:
        """The ActionTemplates its own sections can send (Program.actions)."""
        return ()

    # -- checking --------------------------------------------------------------------------
    def asserted(self, skills: Iterable) -> list:
        """Facts the skills assert (each with ``.fact``, a Literal): their predicates are
        defined before the checks."""
        return []

    # -- running ---------------------------------------------------------------------------
    def runners(self) -> dict[str, Any]:
        """Skill.kind -> body runner for the kinds it executes."""
        return {}

    def impasse_handlers(self) -> dict[str, Callable[[], Any]]:
        """Name -> factory of an impasse handler (Engine(solver=name))."""
        return {}

    def facts(self, state: Any) -> tuple:
        """Base facts it adds to inference this cycle (from its slot of ``state``)."""
        return ()

    def model_reader(self, program: Any) -> Callable[[Iterable], tuple] | None:
        """For the mechanism that keeps a world model: a function checking a model handed
        to Engine.infer and returning its facts."""
        return None

    def intention(self, state: Any) -> tuple:
        """Its parts of what decides the agent's next action (agents/lang/execution/loops.py)."""
        return ()

    # -- the executive process -------------------------------------------------------------
    def memory(self, state: Any) -> dict[str, Any]:
        """What goes out with the actions for the world to hand back ({} for nothing)."""
        return {}

    def remember(self, memory: dict[str, Any], program: Any) -> Any:
        """Its slot value from a memory handed back (StateError when it does not fit);
        None when the memory holds nothing of it."""
        return None

    def carry(self, value: Any, skills: SkillMap) -> tuple[Any, tuple[str, ...]]:
        """Its slot value under a new program whose skills relate to the old ones by
        ``skills``, and what of it is dropped (each a sentence). Default: kept when empty, else
        dropped as a whole (its empty state)."""
        if self.state_type is None or value == self.state_type():
            return value, ()
        return self.state_type(), (f"the {self.name} state ({self.slot}): the new program "
                                   "starts it afresh",)


def slot_kinds(mechanisms: Iterable[Mechanism]) -> tuple[tuple[str, type], ...]:
    """(slot key, state type) of every mechanism that keeps state, in order."""
    return tuple((m.slot, m.state_type) for m in mechanisms
                 if m.slot and m.state_type is not None)


def body_reader(mechanisms: Iterable[Mechanism]) -> Mechanism | None:
    """The mechanism that reads skill bodies, if any."""
    return next((m for m in mechanisms if m.reads_body()), None)
