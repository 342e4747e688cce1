"""BabyAI's compound missions, one step at a time: "go to a key and go to a grey door after you
open the red door" is a tree of instructions (minigrid.envs.babyai.core.verifier: an action,
or two joined by "and", ", then" or "after you") whose verifier notes which parts are done.
The step the agent is on is the first action, in the order the mission asks for them, that is
not done yet; perception maps that step's words as it maps a whole MiniGrid mission."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

_SUCCESS = "success"


def current_step(env: Any) -> str | None:
    """The words of the first action of the env's instructions not done yet; None for an
    env without instructions (MiniGrid's own tasks) or with every action done."""
    instrs = getattr(env, "instrs", None)
    if instrs is None:
        return None
    return next((_words(leaf) for leaf, done in _steps(instrs, False) if not done), None)


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
