"""Hints for a goal the agent cannot work on because what it names is not there.

A goal such as `(package-delivered PACKET9)` for a package that does not exist stays pending
("no path with free resources") and then fails in the problem solver ("no primitive skill
... applies here"): both true, neither says why. The executive adds to such a goal's note
the names in it that no percept of the cycle mentions, so `teleo goal list`, the summary and
the intention say "no percept mentions PACKET9" (issue 12, item 7).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from agents.lang.core.sexpr import Atom, SList, read

_UNMET = frozenset({"pending", "impasse", "failed"})


def goal_names(goal: str) -> list[str]:
    """The constant symbols among a goal's arguments: `(on A ?x)` -> ['A'], `(and (on A B)
    (not (on B C)))` -> ['A', 'B', 'C'] (not concepts, `and`, `not` or test operators, not
    variables, not numbers), each once."""
    forms, diags = read(goal, "<goal>")
    if diags or len(forms) != 1:
        return []
    out: list[str] = []

    def walk(node: object) -> None:
        if isinstance(node, SList):
            for item in node.items[1:]:
                walk(item)
        elif isinstance(node, Atom) and isinstance(node.value, str) and \
                not _is_number(node.value):
            out.append(node.value)

    walk(forms[0])
    return list(dict.fromkeys(out))


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def absent(goal: str, percepts: Iterable[Iterable[Any]]) -> list[str]:
    """The names in ``goal`` that no percept mentions."""
    names = goal_names(goal)
    if not names:
        return []
    seen = {item for p in percepts for item in p if isinstance(item, str)}
    return [n for n in names if n not in seen]


def with_hints(intention: dict[str, Any], percepts: Iterable[Iterable[Any]]) -> dict[str, Any]:
    """``intention`` (Decision.to_dict()) with a hint added to the note of each unmet goal
    that names something no percept mentions this cycle."""
    percepts = list(percepts)
    goals = []
    for g in intention.get("goals", ()):
        missing = absent(str(g.get("goal", "")), percepts) if g.get("status") in _UNMET else []
        if missing:
            hint = f"no percept mentions {', '.join(missing)}: is there such an object?"
            g = {**g, "note": f"{g['note']}; {hint}" if g.get("note") else hint}
        goals.append(g)
    return {**intention, "goals": goals}
