"""An independent STRIPS replay of a plan (issue 35): the domain and problem parsed by
pyperplan's PDDL parser (not the `pddl` package the world uses), each ground action checked
against its operator's typed parameters and preconditions in the current state, its delete
then add effects applied, and the goal checked on the result. Nothing of teleo's world or
engine is used, so a teleo summary that claims a success the replay denies is caught.

Covers what pyperplan parses: STRIPS with typing and domain constants (the five IPC domains of
bench/ipc/suites), and action costs, which it drops itself before parsing (``uncosted``: a
plan's validity does not depend on them); negative preconditions and equality, which
pyperplan does not read, are rewritten for it and tested here (negations.py). An action is a
sequence of lower-case names, ``("stack", "a", "b")``.
"""

from __future__ import annotations

import re
import tempfile
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from pyperplan.pddl.errors import ParseError
from pyperplan.pddl.parser import Parser
from pyperplan.pddl.tree_visitor import SemanticError

from bench.ipc.negations import positive, split

Atom = tuple[str, ...]
"""A ground atom: ("on", "a", "b")."""


class Illegal(Exception):
    """A step that names no operator, has the wrong arguments, or whose precondition is
    false."""


@dataclass(frozen=True)
class Operator:
    """One PDDL action: parameters (name, allowed type names), preconditions, adds and deletes
    as (predicate, argument names) with parameters written ``?x``."""

    name: str
    params: tuple[tuple[str, tuple[str, ...]], ...]
    pre: tuple[Atom, ...]
    adds: tuple[Atom, ...]
    dels: tuple[Atom, ...]
    absent: tuple[Atom, ...] = ()   # negative preconditions (negations.py)
    same: tuple[tuple[str, str], ...] = ()    # (= ?a ?b)
    differ: tuple[tuple[str, str], ...] = ()  # (not (= ?a ?b))


@dataclass(frozen=True)
class StripsTask:
    """A parsed problem: ``kinds`` object -> its type and every supertype; ``init`` and
    ``goal`` ground atoms; ``operators`` by name."""

    operators: dict[str, Operator]
    kinds: dict[str, frozenset[str]]
    init: frozenset[Atom]
    goal: frozenset[Atom]
    goal_absent: frozenset[Atom] = frozenset()   # the goal's negative literals


@dataclass(frozen=True)
class Verdict:
    """The replay's judgement of a plan: ``valid`` (every step legal and the goal holds at the
    end), ``length`` in actions, ``reason`` why not."""

    valid: bool
    length: int
    reason: str = ""
    read: bool = True   # False: the replay's parser could not read the task, so no verdict


def _atom(pred) -> Atom:
    return (pred.name.lower(), *(name.lower() for name, _ in pred.signature))


def _lineage(t) -> frozenset[str]:
    names = set()
    while t is not None:
        names.add(str(t.name).lower())
        t = t.parent
    return frozenset(names)


def _sexp_end(text: str, start: int) -> int:
    depth = 0
    for k in range(start, len(text)):
        depth += {"(": 1, ")": -1}.get(text[k], 0)
        if depth == 0:
            return k + 1
    return len(text)


def has_costs(text: str) -> bool:
    """Whether PDDL ``text`` uses action costs."""
    return re.search(r":action-costs|total-cost", text, re.I) is not None


def uncosted(text: str) -> str:
    """PDDL ``text`` without its action costs: the requirement, the ``:functions`` block,
    ``(increase (total-cost) ...)`` effects (``(and)`` where one is the whole effect), the
    initial values ``(= (f ...) n)`` and the ``:metric``; a problem's ``:requirements``
    too (pyperplan reads none there)."""
    text = re.sub(r";[^\n]*", "", text).replace(":action-costs", "")
    problem = re.search(r"\(\s*problem\b", text, re.I) is not None
    pattern = re.compile(r"\((\s*:functions\b|\s*:metric\b|\s*increase\b|\s*=\s*\("
                         + (r"|\s*:requirements\b" if problem else "") + ")", re.I)
    while (m := pattern.search(text)) is not None:
        end = _sexp_end(text, m.start())
        alone = re.search(r":effect\s*$", text[:m.start()], re.I) is not None
        text = text[:m.start()] + ("(and)" if alone else "") + text[end:]
    return text


def load(domain: str | Path, problem: str | Path) -> StripsTask:
    """Parse ``domain`` and ``problem`` (PDDL files) with pyperplan's parser (action costs
    dropped first)."""
    texts = [Path(domain).read_text(), Path(problem).read_text()]
    read = list(positive(*(uncosted(t) if has_costs(t) else t for t in texts)))
    if read != texts:
        with tempfile.TemporaryDirectory(prefix="strips-") as folder:
            files = [Path(folder) / "domain.pddl", Path(folder) / "problem.pddl"]
            for f, t in zip(files, read, strict=True):
                f.write_text(t)
            return _parsed(*files)
    return _parsed(domain, problem)


def _parsed(domain: str | Path, problem: str | Path) -> StripsTask:
    parser = Parser(str(domain), str(problem))
    dom = parser.parse_domain()
    prob = parser.parse_problem(dom)
    kinds = {name.lower(): _lineage(t) for name, t in {**dom.constants,
                                                       **prob.objects}.items()}
    ops = {}
    for a in dom.actions.values():
        params = tuple((n.lower(), tuple(str(t.name).lower() for t in ts))
                       for n, ts in a.signature)
        holds, absent, same, differ = split(tuple(_atom(p) for p in a.precondition))
        ops[a.name.lower()] = Operator(a.name.lower(), params, holds,
                                       tuple(_atom(p) for p in a.effect.addlist),
                                       tuple(_atom(p) for p in a.effect.dellist),
                                       absent, same, differ)
    goal, absent, same, differ = split(tuple(_atom(p) for p in prob.goal))
    if same or differ:
        raise ValueError("an equality in the goal")   # not in any IPC task
    return StripsTask(ops, kinds, frozenset(_atom(p) for p in prob.initial_state),
                      frozenset(goal), frozenset(absent))


def _text(atom: Sequence[str]) -> str:
    return "(" + " ".join(atom) + ")"


def apply(task: StripsTask, state: frozenset[Atom], step: Sequence[str]) -> frozenset[Atom]:
    """The state after ``step``; raises Illegal naming what is wrong (the false precondition)."""
    name, *args = [str(x).lower() for x in step]
    op = task.operators.get(name)
    if op is None:
        raise Illegal(f"{_text(step)}: no operator {name}; expected one of "
                      f"{', '.join(sorted(task.operators))}")
    if len(args) != len(op.params):
        raise Illegal(f"{_text(step)}: {name} takes {len(op.params)} arguments, got "
                      f"{len(args)}")
    b: dict[str, str] = {}
    for (var, types), value in zip(op.params, args, strict=True):
        kinds = task.kinds.get(value)
        if kinds is None:
            raise Illegal(f"{_text(step)}: {value} is no object of the problem")
        if not kinds & set(types):
            raise Illegal(f"{_text(step)}: {value} is not of type {' or '.join(types)}")
        b[var] = value

    def ground(atom: Atom) -> Atom:
        return (atom[0], *(b.get(x, x) for x in atom[1:]))

    for p in op.pre:
        if ground(p) not in state:
            raise Illegal(f"{_text(step)}: precondition {_text(ground(p))} is false")
    for p in op.absent:
        if ground(p) in state:
            raise Illegal(f"{_text(step)}: precondition (not {_text(ground(p))}) is false")
    for pair, want in (*((p, True) for p in op.same), *((p, False) for p in op.differ)):
        left, right = ground(("=", *pair))[1:]
        if (left == right) != want:
            raise Illegal(f"{_text(step)}: precondition "
                          f"{'(= ' if want else '(not (= '}{left} {right})"
                          f"{'' if want else ')'} is false")
    return (state - {ground(d) for d in op.dels}) | {ground(a) for a in op.adds}


def replay(task: StripsTask, steps: Iterable[Sequence[str]]) -> frozenset[Atom]:
    """The state after ``steps`` from the problem's initial state; raises Illegal at the first
    bad step, saying which (1-based)."""
    state = task.init
    for k, step in enumerate(steps, 1):
        try:
            state = apply(task, state, step)
        except Illegal as exc:
            raise Illegal(f"step {k}: {exc}") from None
    return state


def verify(domain: str | Path, problem: str | Path, steps: Sequence[Sequence[str]]) -> Verdict:
    """``steps`` replayed on the task of ``domain`` and ``problem``; a task pyperplan's parser
    refuses (a predicate it finds undeclared, a requirement it lacks) gets a Verdict with
    ``read`` False and the parser's reason: neither valid nor denied."""
    try:
        task = load(domain, problem)
    except (ParseError, SemanticError, ValueError, KeyError, AttributeError) as exc:
        return Verdict(False, len(steps), f"the replay cannot read this task "
                                          f"({type(exc).__name__}: {exc})", read=False)
    return check(task, steps)


def check(task: StripsTask, steps: Sequence[Sequence[str]]) -> Verdict:
    """Replay ``steps`` and check the goal."""
    try:
        state = replay(task, steps)
    except Illegal as exc:
        return Verdict(False, len(steps), str(exc))
    missing = [*map(_text, sorted(task.goal - state)),
               *(f"(not {_text(a)})" for a in sorted(task.goal_absent & state))]
    if missing:
        return Verdict(False, len(steps), "the goal's " + " ".join(missing[:5])
                       + (" ..." if len(missing) > 5 else "") + " false at the end")
    return Verdict(True, len(steps))


def read_plan(text: str) -> list[tuple[str, ...]]:
    """A plan as pyperplan writes it (one ``(op a b)`` a line) as steps."""
    return [tuple(line.strip().strip("()").lower().split()) for line in text.splitlines()
            if line.strip() and not line.strip().startswith(";")]
