"""PDDL semantics of one ground action on a state (a frozenset of atoms ``(pred, *args)``):
the action's name and arity, each argument an object of the parameter's type (or a type below
it; any of an `either`), every precondition true (an atom in the state, a negated atom not,
an equality of names), then the state minus the delete effects plus the add effects (deletes
first, so an atom both deleted and added holds after, as in PDDL's semantics).

    >>> s, why = apply(task, state, ["*stack", "a", "b"])   # why == "" when it was done

A refused action leaves the state as it was and says why, naming the false literal."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from world.pddl.task import Lit, Operator, Task

Atom = tuple[str, ...]


def ground(lit: Lit, binding: dict[str, str]) -> Lit:
    """``lit`` with its variables replaced by their objects."""
    return Lit(lit.pred, tuple(binding.get(a, a) for a in lit.args), lit.negated)


def holds(lit: Lit, state: frozenset[Atom]) -> bool:
    """Whether the ground literal ``lit`` is true in ``state``."""
    if lit.pred == "=":
        value = lit.args[0] == lit.args[1]
    else:
        value = (lit.pred, *lit.args) in state
    return value != lit.negated


def name_of(action: Any) -> str:
    """An action's operator name: lower-case, without the leading ``*``."""
    return str(action).lstrip("*").lower()


def bind(task: Task, action: Sequence[Any]) -> tuple[Operator | None, dict[str, str], str]:
    """(operator, binding, "") for a well-formed ground action, else (None, {}, why)."""
    if not action or not isinstance(action[0], str):
        return None, {}, f"an action is a list [*name, arg, ...], got {list(action)!r}"
    op = task.domain.operator(name_of(action[0]))
    if op is None:
        known = " ".join(f"*{o.name}" for o in task.domain.operators)
        return None, {}, f"unknown action {action[0]}; the domain {task.domain.name} knows " \
                         f"{known}"
    args = list(action[1:])
    if len(args) != len(op.params):
        shown = " ".join(v for v, _ in op.params)
        return None, {}, f"expected {len(op.params)} argument(s) (*{op.name} {shown}), " \
                         f"got {len(args)}"
    types = task.object_types()
    binding: dict[str, str] = {}
    for k, ((var, wanted), arg) in enumerate(zip(op.params, args, strict=True), start=1):
        if not isinstance(arg, str):
            return None, {}, f"argument {k} {var}: expected an object's name, got {arg!r}"
        name = arg.lower()
        if name not in types:
            return None, {}, f"argument {k} {var}: unknown object {arg}"
        if not set(wanted) & set(types[name]):
            return None, {}, f"argument {k} {var}: {name} is a {types[name][0]}, not " \
                             f"{' or '.join(wanted)}"
        binding[var] = name
    return op, binding, ""


def apply(task: Task, state: frozenset[Atom], action: Sequence[Any]
          ) -> tuple[frozenset[Atom], str]:
    """(the state after ``action``, "") or (``state`` unchanged, why it was refused)."""
    op, binding, why = bind(task, action)
    if op is None:
        return state, why
    for lit in op.pre:
        g = ground(lit, binding)
        if not holds(g, state):
            return state, f"precondition {g.text()} is false"
    return successor(op, binding, state), ""


def successor(op: Operator, binding: dict[str, str], state: frozenset[Atom]
              ) -> frozenset[Atom]:
    """``state`` after ``op`` under ``binding`` (its preconditions not checked)."""
    gone = {(d.pred, *ground(d, binding).args) for d in op.delete}
    new = {(a.pred, *ground(a, binding).args) for a in op.add}
    return frozenset((state - gone) | new)


def satisfied(goal: Sequence[Lit], state: frozenset[Atom]) -> list[Lit]:
    """The goal's literals that are false in ``state`` (none: the goal holds)."""
    return [g for g in goal if not holds(g, state)]
