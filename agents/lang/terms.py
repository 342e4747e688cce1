"""Terms of the language: variables, literals, percept patterns, expressions, percepts, beliefs,
actions (seed 000, "Representation of Knowledge"). Constants are plain str (symbols), int, float."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

from .errors import LangError


@dataclass(frozen=True, slots=True)
class Var:
    """A pattern-match variable ``?name``."""

    name: str

    def __str__(self) -> str:
        return "?" + self.name


def fmt(v: object) -> str:
    """Text of a term: ``ME``, ``20.0``, ``?x``, ``(+ ?x 1)``."""
    if isinstance(v, Var):
        return "?" + v.name
    if isinstance(v, Expr):
        return str(v)
    return str(v)


def sort_key(v: object) -> tuple:
    """Total order over constants (numbers before symbols), for deterministic output."""
    if isinstance(v, (int, float)):
        return (0, v, "")
    return (1, 0, str(v))


def is_const(v: object) -> bool:
    """True for a constant allowed in percepts, beliefs and actions (never bool or None)."""
    return isinstance(v, (str, int, float)) and not isinstance(v, bool)


@dataclass(frozen=True, slots=True)
class Loc:
    """Where a construct was written."""

    source: str
    line: int
    col: int

    def __str__(self) -> str:
        return f"{self.source}:{self.line}:{self.col}"


@dataclass(frozen=True, slots=True)
class Expr:
    """An arithmetic/comparison call ``(op arg...)``; args are constants, Vars or Exprs."""

    op: str
    args: tuple

    def __str__(self) -> str:
        return "(" + " ".join([self.op, *(fmt(a) for a in self.args)]) + ")"

    def variables(self) -> set[Var]:
        out: set[Var] = set()
        for a in self.args:
            if isinstance(a, Var):
                out.add(a)
            elif isinstance(a, Expr):
                out |= a.variables()
        return out


@dataclass(frozen=True, slots=True)
class Literal:
    """A concept reference ``(pred arg...)``, optionally negated ``(not (pred ...))``."""

    pred: str
    args: tuple
    negated: bool = False
    loc: Loc | None = field(default=None, compare=False)

    def __str__(self) -> str:
        core = "(" + " ".join([self.pred, *(fmt(a) for a in self.args)]) + ")"
        return f"(not {core})" if self.negated else core

    def variables(self) -> set[Var]:
        return {a for a in self.args if isinstance(a, Var)}


@dataclass(frozen=True, slots=True)
class PerceptPattern:
    """``(type id attr value ...)`` matching percepts by type, id and a subset of attributes."""

    type: str
    id: object
    attrs: tuple  # ((attr, term), ...)
    loc: Loc | None = field(default=None, compare=False)

    def __str__(self) -> str:
        parts = [self.type, fmt(self.id)]
        for a, t in self.attrs:
            parts += [a, fmt(t)]
        return "(" + " ".join(parts) + ")"

    def variables(self) -> set[Var]:
        terms = [self.id, *(t for _, t in self.attrs)]
        return {t for t in terms if isinstance(t, Var)}


@dataclass(frozen=True, slots=True)
class Test:
    """A ``:tests`` entry: an Expr that must evaluate truthy."""

    expr: Expr
    loc: Loc | None = field(default=None, compare=False)

    def __str__(self) -> str:
        return str(self.expr)

    def variables(self) -> set[Var]:
        return self.expr.variables()


@dataclass(frozen=True)
class Percept:
    """An observed object ``(type id attr value ...)`` (seed 000, Table 3)."""

    type: str
    id: object
    attrs: tuple = ()  # ((attr, value), ...) in the order given

    def __post_init__(self) -> None:
        object.__setattr__(self, "_map", dict(self.attrs))

    def get(self, attr: str, default: object = None) -> object:
        """Value of ``attr`` or ``default``."""
        return self._map.get(attr, default)  # type: ignore[attr-defined]

    def to_list(self) -> list:
        """Neutral form ``[type, id, attr, value, ...]`` (docs/architecture.md)."""
        out = [self.type, self.id]
        for a, v in self.attrs:
            out += [a, v]
        return out

    @classmethod
    def from_list(cls, items: list | tuple) -> Percept:
        """Build from the neutral form; raises LangError naming what is wrong."""
        if isinstance(items, Percept):
            return items
        if not isinstance(items, (list, tuple)) or len(items) < 2 or len(items) % 2:
            raise LangError(f"percept {items!r}: expected [type, id, attr, value, ...] "
                            "(an even number of items, at least 2)")
        if not isinstance(items[0], str):
            raise LangError(f"percept {items!r}: type must be a symbol, got {items[0]!r}")
        for v in items[1:]:
            if not is_const(v):
                raise LangError(f"percept {items!r}: value {v!r} is not a symbol or number")
        attrs = tuple((items[i], items[i + 1]) for i in range(2, len(items), 2))
        for a, _ in attrs:
            if not isinstance(a, str):
                raise LangError(f"percept {items!r}: attribute name {a!r} is not a symbol")
        return cls(items[0], items[1], attrs)

    def __str__(self) -> str:
        return "(" + " ".join(fmt(x) for x in self.to_list()) + ")"


class Belief(NamedTuple):
    """An inferred concept instance ``(pred arg...)``. A NamedTuple (immutable like the frozen
    dataclasses elsewhere) because inference builds thousands per cycle and tuples build fast."""

    pred: str
    args: tuple

    def to_list(self) -> list:
        """Neutral form ``[pred, arg1, ...]``."""
        return [self.pred, *self.args]

    @classmethod
    def from_list(cls, items: list | tuple) -> Belief:
        return cls(items[0], tuple(items[1:]))

    def __str__(self) -> str:
        return "(" + " ".join([self.pred, *(fmt(a) for a in self.args)]) + ")"


@dataclass(frozen=True, slots=True)
class Action:
    """A primitive action with evaluated arguments, e.g. ``(*gas 6.25)``."""

    name: str
    args: tuple = ()

    def to_list(self) -> list:
        """Neutral form ``["*gas", 6.25]``."""
        return [self.name, *self.args]

    @classmethod
    def from_list(cls, items: list | tuple) -> Action:
        return cls(items[0], tuple(items[1:]))

    def __str__(self) -> str:
        return "(" + " ".join([self.name, *(fmt(a) for a in self.args)]) + ")"


@dataclass(frozen=True, slots=True)
class ActionTemplate:
    """An action as written in a skill: ``(*steer (* ?angle 2))``; evaluated at execution time."""

    name: str
    args: tuple
    loc: Loc | None = field(default=None, compare=False)

    def __str__(self) -> str:
        return "(" + " ".join([self.name, *(fmt(a) for a in self.args)]) + ")"

    def variables(self) -> set[Var]:
        out: set[Var] = set()
        for a in self.args:
            if isinstance(a, Var):
                out.add(a)
            elif isinstance(a, Expr):
                out |= a.variables()
        return out
