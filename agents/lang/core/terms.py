"""Terms of the language: variables, literals, percept patterns, expressions, percepts, beliefs,
actions (seed 000, "Representation of Knowledge"). Constants are plain str (symbols), int, float."""

from __future__ import annotations

from dataclasses import FrozenInstanceError, dataclass, field
from threading import Lock
from typing import NamedTuple
from weakref import WeakValueDictionary

from .errors import LangError


class Var:
    """A pattern-match variable ``?name``. Immutable, and one object per name while any is
    alive (``Var("x") is Var("x")``), so that it is equal and hashed by identity, in C rather
    than by a Python ``__eq__``/``__hash__``: variables key every binding the matcher makes."""

    __slots__ = ("name", "__weakref__")
    name: str

    def __new__(cls, name: str) -> Var:
        v = _VARS.get(name)
        if v is None:
            with _MAKING:   # two threads making the same name get the same object
                v = _VARS.get(name)
                if v is None:
                    v = object.__new__(cls)
                    object.__setattr__(v, "name", name)
                    _VARS[name] = v
        return v

    def __setattr__(self, key: str, value: object) -> None:
        raise FrozenInstanceError(f"cannot assign to field {key!r}")

    def __delattr__(self, key: str) -> None:
        raise FrozenInstanceError(f"cannot delete field {key!r}")

    def __reduce__(self) -> tuple:
        return (Var, (self.name,))

    def __repr__(self) -> str:
        return f"Var(name={self.name!r})"

    def __str__(self) -> str:
        return "?" + self.name


_VARS: WeakValueDictionary[str, Var] = WeakValueDictionary()  # name -> its one live Var
_MAKING = Lock()


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
        core = "(" + " ".join([self.pred, *map(fmt, self.args)]) + ")"
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


class Percept:
    """An observed object ``(type id attr value ...)`` (seed 000, Table 3). Immutable; equal and
    hashed by (type, id, attrs). A plain slotted class rather than a frozen dataclass because the
    executive's percept index makes one per object per cycle (``Percept.of_row``): ``attrs``
    and the attribute map are then built on first use."""

    __slots__ = ("type", "id", "_row", "_attrs", "_m")

    def __init__(self, type: str, id: object, attrs: tuple = ()) -> None:  # noqa: A002
        _set(self, "type", type)
        _set(self, "id", id)
        _set(self, "_row", None)
        _set(self, "_attrs", tuple(attrs))
        _set(self, "_m", None)

    @classmethod
    def of_row(cls, row: list | tuple) -> Percept:
        """From an already validated neutral list (no checks: used after ``intake``)."""
        self = _new(cls)
        _set(self, "type", row[0])
        _set(self, "id", row[1])
        _set(self, "_row", tuple(row))
        _set(self, "_attrs", None)
        _set(self, "_m", None)
        return self

    @property
    def attrs(self) -> tuple:
        """((attr, value), ...) in the order given."""
        a = self._attrs
        if a is None:
            row = self._row
            a = tuple(zip(row[2::2], row[3::2], strict=True))
            _set(self, "_attrs", a)
        return a

    @property
    def _map(self) -> dict:
        m = self._m
        if m is None:
            if self._row is not None:
                row = self._row
                m = dict(zip(row[2::2], row[3::2], strict=True))
            else:
                m = dict(self._attrs)
            _set(self, "_m", m)
        return m

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"Percept is immutable: cannot set {name}")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"Percept is immutable: cannot delete {name}")

    def __eq__(self, other: object) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        return (self.type, self.id, self.attrs) == (other.type, other.id, other.attrs)

    def __hash__(self) -> int:
        return hash((self.type, self.id, self.attrs))

    def __repr__(self) -> str:
        return f"Percept(type={self.type!r}, id={self.id!r}, attrs={self.attrs!r})"

    def __reduce__(self) -> tuple:
        return (Percept, (self.type, self.id, self.attrs))

    def get(self, attr: str, default: object = None) -> object:
        """Value of ``attr`` or ``default``."""
        return self._map.get(attr, default)

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
        check_row(items)
        return cls.of_row(items)

    def __str__(self) -> str:
        return "(" + " ".join(fmt(x) for x in self.to_list()) + ")"


def check_row(items: object) -> None:
    """Raise LangError naming the percept unless ``items`` is a valid neutral percept list."""
    if not isinstance(items, (list, tuple)) or len(items) < 2 or len(items) % 2:
        raise LangError(f"percept {items!r}: expected [type, id, attr, value, ...] "
                        "(an even number of items, at least 2)")
    if not isinstance(items[0], str):
        raise LangError(f"percept {items!r}: type must be a symbol, got {items[0]!r}")
    for v in items[1:]:
        if not is_const(v):
            raise LangError(f"percept {items!r}: value {v!r} is not a symbol or number")
    for a in items[2::2]:
        if not isinstance(a, str):
            raise LangError(f"percept {items!r}: attribute name {a!r} is not a symbol")


_set = object.__setattr__
_new = object.__new__


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
