"""Hints for a goal the agent cannot work on because what it names is not there.

A goal such as `(package-delivered PACKET9)` for a package that does not exist stays pending
("no path with free resources") and then fails in the problem solver ("no primitive skill
... applies here"): both true, neither says why. The executive adds to such a goal's note
the names in it that no percept of the cycle mentions, so `teleo goal list`, the summary and
the intention say "no percept mentions PACKET9".
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from agents.lang.core.program import Program
from agents.lang.core.sexpr import Atom, SList, read
from agents.lang.core.terms import PerceptPattern, Var

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


def with_hints(intention: dict[str, Any], percepts: Iterable[Iterable[Any]],
               program: Program | None = None) -> dict[str, Any]:
    """``intention`` (Decision.to_dict()) with a hint added to the note of each unmet goal
    that names something no percept mentions this cycle, or (given the agent's
    ``program``) whose concept's percepts, with the goal's arguments, match no percept."""
    percepts = list(percepts)
    goals = []
    for g in intention.get("goals", ()):
        text, status = str(g.get("goal", "")), g.get("status")
        missing = absent(text, percepts) if status in _UNMET else []
        hints = [f"no percept mentions {', '.join(missing)}: is there such an object?"] \
            if missing else []
        if program is not None and status in _GIVEN_UP:
            hints.append(unmatched(text, program, percepts, set(missing)))
        hint = "; ".join(h for h in hints if h)
        if hint:
            g = {**g, "note": f"{g['note']}; {hint}" if g.get("note") else hint}
        goals.append(g)
    return {**intention, "goals": goals}


_GIVEN_UP = frozenset({"impasse", "failed"})


def unmatched(goal: str, program: Program, percepts: list[Iterable[Any]],
              told: set[str] = frozenset()) -> str:
    """A hint for a goal whose concept can hold only with a percept that is not there: each
    clause of the concept has a percept pattern that, with the goal's arguments put for the
    head's variables, matches no percept of the cycle (`(at-address ME 12 A)` is not
    the skills' fault where no package has address 12 on A); "" otherwise, and
    when the pattern names only names ``told`` (no percept mentions them: said already)."""
    forms, diags = read(goal, "<goal>")
    if diags or len(forms) != 1 or not isinstance(forms[0], SList) or not forms[0].items:
        return ""
    head, *args = [item.value if isinstance(item, Atom) else None for item in forms[0].items]
    clauses = program.concepts.get(head, ()) if isinstance(head, str) else ()
    rows = [list(p) for p in percepts]
    missing = []
    for clause in clauses:
        if len(clause.head.args) != len(args) or clause.head.negated:
            return ""
        given = {v: a for v, a in zip(clause.head.args, args, strict=True)
                 if isinstance(v, Var) and a is not None and not str(a).startswith("?")}
        lost = next((p for p in clause.percepts if not any(_fits(p, given, r) for r in rows)),
                    None)
        if lost is None:
            return ""
        named = {str(given[t]) for t in (lost.id, *(t for _, t in lost.attrs))
                 if isinstance(t, Var) and t in given}
        if named <= told:
            return ""
        missing.append(_shown(lost, given))
    if not missing:
        return ""
    return (f"no percept matches {missing[0]} ({head} needs it"
            f"{' or one of ' + str(len(missing) - 1) + ' more' if len(missing) > 1 else ''})")


def _fits(pattern: PerceptPattern, given: dict[Var, Any], row: list[Any]) -> bool:
    """Whether percept ``row`` ([type, id, attr, value, ...]) fits ``pattern`` in what the
    goal gives (its id and attributes that are head variables bound by the goal)."""
    if not row or row[0] != pattern.type:
        return False
    values = dict(zip(row[2::2], row[3::2], strict=False))
    pairs = [(pattern.id, row[1] if len(row) > 1 else None),
             *((term, values.get(attr, _NONE)) for attr, term in pattern.attrs)]
    return all(_same(given[term], value) for term, value in pairs
               if isinstance(term, Var) and term in given)


_NONE = object()


def _same(wanted: Any, value: Any) -> bool:
    if value is _NONE:
        return False
    if isinstance(value, int | float) and not isinstance(value, bool):
        try:
            return float(wanted) == float(value)
        except (TypeError, ValueError):
            return False
    return str(wanted) == str(value)


def _shown(pattern: PerceptPattern, given: dict[Var, Any]) -> str:
    """The pattern with the goal's values put in: `(package ?p address 12 street A)`."""
    def term(t: Any) -> str:
        return str(given[t]) if isinstance(t, Var) and t in given else str(t)
    parts = [pattern.type, term(pattern.id)]
    for attr, t in pattern.attrs:
        if isinstance(t, Var) and t in given:
            parts += [attr, term(t)]
    return "(" + " ".join(parts) + ")"
