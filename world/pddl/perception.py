"""What an agent perceives of a PDDL problem (percepts.md), a pure function of a snapshot dict:

    (object a type block)       an object, once for its type and once for each type above it
    (on _ arg1 a arg2 b)        the atom (on a b): the predicate's name is the percept's type,
                                the k-th argument the value of argk, the id `_` (no PDDL name)
    (handempty _)               an atom without arguments

Objects first (by name, then type), then the atoms sorted. The atoms' id is `_` rather than
their first argument so that the only percepts whose id is an object's name are its object
percepts: the problem solver names a learned skill's variable after the type of the first
percept (in name order) whose id is the constant it replaces (agents/lang/solving/task.py,
``Task.type_of``), and binds it through a pattern of that type. With `(at pkg1 ...)` as a
percept, a skill learned about pkg1 would need pkg1 to be `at` somewhere; with `(object pkg1)`
it applies to any package."""

from __future__ import annotations

from typing import Any

from world.errors import WorldError

OBJECT = "object"   # the type of an object's percepts
ATOM = "_"          # the id of every atom's percept


def atom_percept(atom: list[str] | tuple[str, ...]) -> list[str]:
    """The percept of one atom ``(pred, a1, ..., an)``: ``[pred, "_", "arg1", a1, ...]``."""
    pred, *args = atom
    out = [pred, ATOM]
    for k, a in enumerate(args, start=1):
        out += [f"arg{k}", a]
    return out


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """Every agent sees the whole state."""
    try:
        objects = [[OBJECT, o, "type", t] for o, types in snapshot["objects"] for t in types]
        atoms = [atom_percept(a) for a in snapshot["atoms"]]
    except (KeyError, TypeError, ValueError) as exc:
        raise WorldError(f"pddl: a snapshot without its objects or atoms: {exc!r:.80}") from None
    return objects + atoms
