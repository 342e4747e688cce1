"""BabyAI's compound missions, one step at a time: "go to a key and go to a grey door after you
open the red door" is a tree of instructions (minigrid.envs.babyai.core.verifier: an action,
or two joined by "and", ", then" or "after you") whose verifier notes which parts are done.
The step the agent is on is the first action, in the order the mission asks for them, that is
not done yet; perception maps that step's words as it maps a whole MiniGrid mission."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

_SUCCESS = "success"


def current_step(env: Any) -> tuple[str, dict[str, list[str]]] | None:
    """The first action of the env's instructions not done yet: its words, and the names of
    the objects its descriptions pick ("wanted": the one to act on, "anchor": the one to put
    it next to), as the verifier picked them when the level was made, "on your left" and
    "behind you" included (from where the agent then stood); {} for the names when one of
    them picks no object perception named. None for an env without instructions (MiniGrid's
    own tasks) or with every action done."""
    instrs = getattr(env, "instrs", None)
    if instrs is None:
        return None
    leaf = next((leaf for leaf, done in _steps(instrs, False) if not done), None)
    if leaf is None:
        return None
    descs = {"wanted": getattr(leaf, "desc", None) or getattr(leaf, "desc_move", None),
             "anchor": getattr(leaf, "desc_fixed", None)}
    named = {role: _names(desc) for role, desc in descs.items() if desc is not None}
    # an object perception has not named (none on the grid): the words alone pick them
    return _words(leaf), named if all(named.values()) else {}


def _names(desc: Any) -> list[str]:
    """The names perception gave the objects a description picks (world/gym/families/
    minigrid.py names each object it captures)."""
    names = (getattr(obj, "_teleo_name", None) for obj in getattr(desc, "obj_set", ()) or ())
    return sorted(n for n in names if n)


_VERBS = {"GoToInstr": "go to", "PickupInstr": "pick up", "OpenInstr": "open"}


def _words(leaf: Any) -> str:
    """An action's words, from its object descriptions alone (the verifier's own ``surface``
    asserts the object is still on the grid, which a carried one is not)."""
    name = type(leaf).__name__
    if name == "PutNextInstr":
        return f"put a {_desc(leaf.desc_move)} next to a {_desc(leaf.desc_fixed)}"
    return f"{_VERBS.get(name, name)} a {_desc(getattr(leaf, 'desc', None))}"


def _desc(desc: Any) -> str:
    """``red ball``, ``object`` (any type), ``grey object``."""
    color, kind = getattr(desc, "color", None), getattr(desc, "type", None)
    return " ".join(w for w in (color, kind or "object") if w)


def _steps(instr: Any, done: bool) -> Iterator[tuple[Any, bool]]:
    """The actions of ``instr`` in the order they are asked for, each with whether it is done
    (``done``: its parent says the whole of ``instr`` is)."""
    a, b = getattr(instr, "instr_a", None), getattr(instr, "instr_b", None)
    if a is None or b is None:
        yield instr, done
        return
    parts = [(a, done or getattr(instr, "a_done", False) == _SUCCESS),
             (b, done or getattr(instr, "b_done", False) == _SUCCESS)]
    if type(instr).__name__ == "AfterInstr":   # "A after you B": B first
        parts.reverse()
    for part, part_done in parts:
        yield from _steps(part, part_done)
