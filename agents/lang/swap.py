"""A running agent's program swapped for another (`teleo program load`; docs/language.md,
"Changing a running agent's program"). Pure: the process modules build the new Engine and hand
the old state here; what comes back is the state under the new program and what of the old
one was dropped, each a sentence.

What carries over, where it still means something:
- the user goals whose goal the new program can still pursue (its concepts, its arity), with
  their ids, priorities, ends and failures; the program's own goals are the new program's
  (p1..pn in its order: one with the same id and goal as before keeps its path);
- the learned skills that still read against the new program (checked as a learned file is);
- each goal's remembered skill path whose every skill is in the new program unchanged (the same
  clause, wherever it is now written: renumbered), and the goals that acted last cycle;
- each mechanism's state as the mechanism says (Mechanism.carry): SCS body threads and
  do-best records of the skills still there, the world model; the means-ends goal stacks and
  the planner's agenda start afresh when they held something.
The loop watch goes on for the goals kept."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, fields, is_dataclass, replace
from typing import Any

from .core.errors import LangError
from .core.mechanism import SkillMap
from .core.program import Program, Skill
from .engine import Engine
from .execution.loops import LoopState
from .execution.state import EngineState, StoredStep
from .reading.extend import extend_program

_NOT_THE_CLAUSE = frozenset({"loc", "number", "index"})  # where it is written, not what it says
MAX_SAID = 160  # [characters] of a learned clause in a sentence


@dataclass(frozen=True)
class Carried:
    """The engine state under the new program, and what of the old one was dropped."""

    state: EngineState
    dropped: tuple[str, ...]


def carry_state(old: Engine, new: Engine, state: EngineState) -> Carried:
    """``state`` (of ``old``'s program) carried over to ``new``'s program (module doc)."""
    dropped: list[str] = []
    learned = _learned(new.program, state.learned, dropped)
    skills = skill_map(extend_program(old.program, state.learned),
                       extend_program(new.program, learned))
    fresh = new.initial_state(seed=state.seed, learned=learned)
    goals = _goals(new, state, fresh, dropped)
    same = {(e.id, e.text) for e in state.goals}   # a program goal keeps its id's path when
    kept = {e.id for e in goals if e.origin == "user" or (e.id, e.text) in same}  # unmoved
    paths = tuple(p for p in (_path(gid, steps, skills, dropped) for gid, steps in state.paths
                              if gid in kept) if p is not None)
    with_path = {gid for gid, _ in paths}
    slots = []
    for m in new.mechanisms:
        if m.slot and m.state_type is not None:
            value, said = m.carry(getattr(state, m.slot), skills)
            slots.append((m.slot, value))
            dropped.extend(said)
    carried = EngineState(goals, paths, max(state.next_seq, fresh.next_seq), state.cycle,
                          state.seed, tuple(g for g in state.active if g in with_path),
                          tuple((g, w) for g, w in state.failed if g in kept), learned,
                          LoopState(tuple(w for w in state.loops.watches if w.goal_id in kept)),
                          slots=tuple(slots))
    return Carried(carried, tuple(dropped))


def skill_map(old: Program, new: Program) -> SkillMap:
    """Each skill of ``old`` that ``new`` holds unchanged (module doc): old -> new number and
    name. Two equal clauses pair in the order they are written."""
    free: dict[Any, list[Skill]] = {}
    for s in new.skills:
        free.setdefault(clause_shape(s), []).append(s)
    numbers, names = {}, {}
    for s in old.skills:
        same = free.get(clause_shape(s))
        if same:
            twin = same.pop(0)
            numbers[s.number], names[s.name] = twin.number, twin.name
    return SkillMap(numbers, names)


def clause_shape(x: Any) -> Any:
    """What a clause says, as a hashable value: its fields but where it is written."""
    if is_dataclass(x) and not isinstance(x, type):
        return (type(x).__name__, tuple((f.name, clause_shape(getattr(x, f.name)))
                                        for f in fields(x) if f.name not in _NOT_THE_CLAUSE))
    if isinstance(x, tuple | list):
        return tuple(clause_shape(v) for v in x)
    if isinstance(x, dict):
        return tuple(sorted((repr(k), clause_shape(v)) for k, v in x.items()))
    if x is None or isinstance(x, str | int | float | bool):
        return x
    return (type(x).__name__, repr(x))


def _learned(program: Program, clauses: Iterable[str], dropped: list[str]) -> tuple[str, ...]:
    kept: list[str] = []
    for clause in clauses:
        try:
            extend_program(program, (*kept, clause))
        except LangError as exc:
            first = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
            dropped.append(f"learned skill {' '.join(clause.split())[:MAX_SAID]}: it does not "
                           f"read against the new program ({first})")
            continue
        kept.append(clause)
    return tuple(kept)


def _goals(new: Engine, state: EngineState, fresh: EngineState, dropped: list[str]) -> tuple:
    """The new program's goals, then each user goal the new program can still pursue."""
    goals = list(fresh.goals)
    for e in state.goals:
        if e.origin != "user":
            if not any(g.text == e.text for g in fresh.goals):
                dropped.append(f"program goal {e.id} {e.text}: not a goal of the new program")
            continue
        try:   # checked as a goal posted to the new program is
            lit = new.add_goal(EngineState(), e.text, e.priority, e.id).goals[0].literal
        except LangError as exc:
            why = str(exc).removeprefix(f"goal {e.text}: ")
            dropped.append(f"goal {e.id} {e.text}: {why}")
            continue
        goals.append(replace(e, literal=lit))
    return tuple(goals)


def _path(goal_id: str, steps: tuple[StoredStep, ...], skills: SkillMap, dropped: list[str]
          ) -> tuple[str, tuple[StoredStep, ...]] | None:
    gone = [s.skill_name for s in steps if s.skill not in skills.numbers]
    if gone:
        dropped.append(f"the skill path of goal {goal_id}: skill {gone[0]} is not in the new "
                       "program")
        return None
    return goal_id, tuple(replace(s, skill=skills.numbers[s.skill],
                                  skill_name=skills.names.get(s.skill_name, s.skill_name))
                          for s in steps)
