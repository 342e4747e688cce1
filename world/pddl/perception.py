"""What an agent perceives of a PDDL problem (percepts.md), a pure function of a snapshot dict:

    (object a type block)       an object, once for its type and once for each type above it
    (on a arg2 b)               the atom (on a b): the predicate's name is the percept's type,
                                the first argument its id, the k-th the value of argk
    (clear a)                   a one-place atom: the id alone
    (handempty true)            an atom without arguments: the id `true`

Objects first (by name, then type), then the atoms sorted."""

from __future__ import annotations

from typing import Any

from world.errors import WorldError

OBJECT = "object"   # the type of an object's percepts
NULLARY = "true"    # the id of an atom without arguments


def atom_percept(atom: list[str] | tuple[str, ...]) -> list[str]:
    """The percept of one atom ``(pred, a1, ..., an)``."""
    pred, *args = atom
    if not args:
        return [pred, NULLARY]
    out = [pred, args[0]]
    for k, a in enumerate(args[1:], start=2):
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
