"""The data the pddl world runs: a PDDL domain and problem as plain, frozen data (the STRIPS
fragment: typing with type hierarchies and `either`, constants, equality, negative
preconditions), read by files.py. Names are lower-cased (PDDL is case-insensitive); a variable
keeps its ``?``."""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

ROOT_TYPE = "object"


@dataclass(frozen=True)
class Lit:
    """A literal: ``pred`` with ``args`` (names, or variables ``?x``); pred "=" is equality."""

    pred: str
    args: tuple[str, ...]
    negated: bool = False

    def text(self) -> str:
        """PDDL text: ``(on a b)``, ``(not (= ?x ?y))``."""
        core = "(" + " ".join((self.pred, *self.args)) + ")"
        return f"(not {core})" if self.negated else core


@dataclass(frozen=True)
class Operator:
    """A STRIPS operator: parameters (variable, its types: more than one for `either`),
    preconditions, add and delete effects."""

    name: str
    params: tuple[tuple[str, tuple[str, ...]], ...]
    pre: tuple[Lit, ...]
    add: tuple[Lit, ...]
    delete: tuple[Lit, ...]


@dataclass(frozen=True)
class DomainModel:
    """A domain: its types (type, parent), constants (name, type), predicates (name,
    parameters as in Operator) and operators, in the file's order where it has one;
    ``notes``: what of the file the world ignores (action costs: costs.py), for its user."""

    name: str
    types: tuple[tuple[str, str], ...]
    constants: tuple[tuple[str, str], ...]
    predicates: tuple[tuple[str, tuple[tuple[str, tuple[str, ...]], ...]], ...]
    operators: tuple[Operator, ...]
    path: str = ""
    notes: tuple[str, ...] = ()

    def ancestors(self, t: str) -> tuple[str, ...]:
        """``t`` and every type above it, ``object`` last."""
        parent = dict(self.types)
        out = [t]
        while out[-1] != ROOT_TYPE and len(out) <= len(parent) + 1:
            out.append(parent.get(out[-1], ROOT_TYPE))
        return tuple(dict.fromkeys(out))

    def operator(self, name: str) -> Operator | None:
        return next((o for o in self.operators if o.name == name), None)

    def arity(self, pred: str) -> int | None:
        return next((len(ps) for p, ps in self.predicates if p == pred), None)


@dataclass(frozen=True)
class Task:
    """A problem of a domain: objects (the domain's constants, then the problem's, sorted),
    the initial atoms (tuples ``(pred, *args)``) and the goal's literals."""

    domain: DomainModel
    name: str
    objects: tuple[tuple[str, str], ...]
    init: frozenset[tuple[str, ...]]
    goal: tuple[Lit, ...]
    path: str = ""

    def object_types(self) -> dict[str, tuple[str, ...]]:
        """Each object's type and the types above it."""
        return {o: self.domain.ancestors(t) for o, t in self.objects}


def position(path: str | Path, text: str, index: int) -> str:
    """``path:line:col`` of character ``index`` of ``text`` (1-based)."""
    line = text.count("\n", 0, index) + 1
    col = index - (text.rfind("\n", 0, index) + 1) + 1
    return f"{path}:{line}:{col}"


def locate(path: str | Path, text: str, name: str, after: str = "") -> str:
    """``path:line:col`` of the first whole-word ``name`` in ``text`` (after the first
    ``after``, comments skipped), or ``path`` alone when it is not found."""
    start = 0
    if after:
        m = re.search(re.escape(after), text, re.I)
        start = m.end() if m else 0
    for m in re.finditer(rf"(?<![\w?-]){re.escape(name)}(?![\w-])", text[start:], re.I):
        k = start + m.start()
        line_start = text.rfind("\n", 0, k) + 1
        if ";" not in text[line_start:k]:
            return position(path, text, k)
    return str(path)


def uncommented(text: str) -> str:
    """``text`` with each comment blanked out (same length: positions stay)."""
    return re.sub(r";[^\n]*", lambda m: " " * len(m.group()), text)
