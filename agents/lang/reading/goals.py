"""Goal entries, the prioritized goal list and goal instances (seed 000, "Adding Goal Priorities").

Priority: lower number = more important. Program goals get 1..n in file order; an entry with
priority P ranks after every entry whose priority is <= P that was placed before it (ties keep
insertion order, ``seq``).

Instances of a goal with variables, e.g. ``(at-desired-speed ?any)``, "every vehicle" (seed 000,
"Teleoreactive Logic Programs"): for each clause of the goal's concept, the clause head is
unified with the goal and the clause's ``:percepts`` are matched against this cycle's percepts
as kinds of object, without the attributes they require to have a constant value (those say
whether the concept holds for the object, not which objects it is about: with ``(package ?p
delivered T)`` the goal ``(package-delivered ?any)`` is about every package, delivered or not);
each match fixes the goal variables that the head takes from percepts. The distinct results are
the instances; the goal is satisfied when every instance holds. A goal variable that some clause
of its concept does not take from its :percepts could not mean "every instance", so such a goal
is refused (``enumerable``).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

from ..core.conjunction import (
    Conjunction,
    Goal,
    conjunction_holds,
    goal_literals,
    is_conjunction,
    read_conjunction,
)
from ..core.errors import GoalError
from ..core.limits import MAX_GOAL_CHARS, shorten
from ..core.matcher import binding_key, holds, solve, unify_head
from ..core.program import Program
from ..core.sexpr import Atom, SList, read
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, PerceptPattern, Var, sort_key
from .parser import Parser, Parts


@dataclass(frozen=True, slots=True)
class GoalEntry:
    """One goal in the list: ``origin`` is "program" or "user". ``once``: dropped from pursuit
    once achieved, not kept as a maintenance goal; ``deadline``: the engine cycle by which it
    must be achieved, else it fails (-1: none); ``ended``: why a once goal or one with a
    deadline is over ("" while it is pursued; agents/lang/execution/executive.py)."""

    id: str
    literal: Goal
    priority: int
    seq: int
    origin: str = "user"
    once: bool = False
    deadline: int = -1
    ended: str = ""
    text: str = field(init=False, repr=False, compare=False)  # the literal's text, made once

    def __post_init__(self) -> None:
        object.__setattr__(self, "text", str(self.literal))


def ordered(entries: tuple[GoalEntry, ...]) -> list[GoalEntry]:
    """Goals most important first: by priority, then insertion order."""
    return sorted(entries, key=lambda e: (e.priority, e.seq))


def parse_goal(text: str, program: Program | None = None) -> Goal:
    """Read a goal such as ``(package-delivered PACKET2)`` or ``(and (on A B) (on B C))``;
    check concepts and arities if given a program. Raises GoalError with the reason (and the
    column for a reading error); a text over MAX_GOAL_CHARS is refused before it is read."""
    if len(text) > MAX_GOAL_CHARS:
        raise GoalError(f"goal {shorten(text)!r}: longer than {MAX_GOAL_CHARS} characters")
    forms, diags = read(text, "<goal>")
    errors = [d for d in diags if d.severity == "error"]
    if errors:
        raise GoalError(f"goal {text!r}: {_where(text, errors[0].line, errors[0].col)}: "
                        f"{errors[0].message}")
    if len(forms) != 1 or not isinstance(forms[0], SList) or not forms[0].items:
        raise GoalError(f"goal {text!r}: expected one list such as (package-delivered PACKET2)"
                        " or (and (on A B) (on B C))")
    goal = _conjunction(text, forms[0]) if is_conjunction(forms[0]) else _literal(text, forms[0])
    if program is not None:
        for lit in goal_literals(goal):
            what = "" if lit is goal else f" (conjunct {lit})"
            if lit.pred not in program.arity:
                raise GoalError(f"goal {text}: undefined concept '{lit.pred}'{what}")
            if program.arity[lit.pred] != len(lit.args):
                raise GoalError(f"goal {text}: concept {lit.pred} takes "
                                f"{program.arity[lit.pred]} argument(s), got {len(lit.args)}"
                                f"{what}")
    return goal


def _literal(text: str, form: SList) -> Literal:
    items = form.items
    if not all(isinstance(x, Atom) for x in items) or not isinstance(items[0].value, str):
        raise GoalError(f"goal {text!r}: expected (concept arg ...) with constants or "
                        "variables, or (and ...) of such literals, (not ...) and tests")
    return Literal(items[0].value, tuple(x.value for x in items[1:]))


def _conjunction(text: str, form: SList) -> Conjunction:
    parts = Parts()
    conj = read_conjunction(Parser("<goal>", parts), form)
    problems = [d for d in parts.diags if d.severity == "error"]
    if conj is None or problems:
        d = problems[0]
        raise GoalError(f"goal {text!r}: {_where(text, d.line, d.col)}: {d.message}")
    return conj


def _where(text: str, line: int, col: int) -> str:
    """A position in a goal's text, in words: it is a string typed by a user, not a file
    (``column 7``; ``line 2, column 1`` when the text has several lines)."""
    return f"column {col}" if "\n" not in text else f"line {line}, column {col}"


def instances(goal: Goal, program: Program, pidx: PerceptIndex) -> list[Literal]:
    """The instances of ``goal`` this cycle, sorted (see module docstring); a conjunction is
    its own one instance (its variables are existential)."""
    if isinstance(goal, Conjunction):
        return [goal]
    gvars = goal.variables()
    if not gvars:
        return [goal]
    found: dict[tuple, Literal] = {}
    for clause in program.concepts.get(goal.pred, ()):
        b = unify_head(clause.head, goal)
        if b is None:
            continue
        if not clause.percepts:
            found[_key(goal)] = goal
            continue
        for sol in solve(list(_kinds(clause.percepts)), b, pidx, FactStore()):
            args = []
            for g, h in zip(goal.args, clause.head.args, strict=True):
                value = sol.get(h, h) if isinstance(h, Var) else h
                args.append(g if isinstance(value, Var) else (g if not isinstance(g, Var)
                                                              else value))
            inst = Literal(goal.pred, tuple(args))
            found.setdefault(_key(inst), inst)
    return [found[k] for k in sorted(found)]


_KINDS: dict[int, tuple] = {}  # id(patterns) -> (patterns, their kinds): see _kinds


def _kinds(patterns: tuple[PerceptPattern, ...]) -> tuple[PerceptPattern, ...]:
    """The percept patterns without their constant-valued attributes: which objects a goal
    with variables is about (see the module docstring). Made once per clause's patterns,
    found by identity (hashing them, as a cache by value would, costs more than the walk it
    saves); the entry holds the patterns, so their id stays theirs."""
    got = _KINDS.get(id(patterns))
    if got is None or got[0] is not patterns:
        if len(_KINDS) >= 4096:
            _KINDS.clear()
        got = _KINDS[id(patterns)] = (patterns, tuple(
            replace(p, attrs=tuple((a, t) for a, t in p.attrs if isinstance(t, Var)))
            for p in patterns))
    return got[1]


def enumerable(goal: Goal, program: Program) -> str:
    """"" if every instance of ``goal`` can be found from percepts (see the module doc), else
    why not: a goal variable that a clause of its concept binds only through :relations.
    A conjunction's variables are existential: always ""."""
    if isinstance(goal, Conjunction):
        return ""
    for i, arg in enumerate(goal.args):
        if not isinstance(arg, Var):
            continue
        for clause in program.concepts.get(goal.pred, ()):
            if len(clause.head.args) != len(goal.args):
                continue  # an arity mismatch, reported by the checker
            head = clause.head.args[i]
            if isinstance(head, Var) and not any(head in p.variables() for p in clause.percepts):
                return (f"variable {arg} cannot mean every instance: clause "
                        f"{goal.pred}#{clause.index} takes ?{head.name} from no percept; write "
                        f"the goal with a constant there, or give the concept a :percepts "
                        f"pattern for it")
    return ""


def satisfied(inst: Goal, store: FactStore) -> bool:
    """True if a belief matches the instance (remaining variables existential), or, for a
    conjunction, if one binding makes every conjunct hold."""
    if isinstance(inst, Conjunction):
        return conjunction_holds(inst, store)
    return holds(inst, {}, store)


def _key(lit: Literal) -> tuple:
    return tuple((1, a.name) if isinstance(a, Var) else (0, sort_key(a)) for a in lit.args)


__all__ = ["GoalEntry", "ordered", "parse_goal", "instances", "enumerable", "satisfied",
           "binding_key"]
