"""The step tree of an SCS skill body, read from ``:body`` (seed 002, Appendix C).

A step is an atomic action ``(*name arg ...)``, an atomic group ``(atomic STEP ...)``, a
subgoal ``(LITERAL)``, a world-model update ``(assert (FACT))`` / ``(retract (FACT))``, a
wait point ``(wait COND ...)`` (seed 002, section 3, "Multiple Threads of Execution"), or a
construct ``(NAME MODS STEP ...)``: ``do``, ``do-all``, ``do-any``, ``repeat`` and their
starred forms take steps; ``do-first`` takes ``(CONDS STEP)`` pairs and ``do-best``
``(CONDS :utility EXPR [:reward EXPR] STEP)`` alternatives. MODS are ``:while``,
``:until``, ``:when``, ``:unless``, each followed by a list of conditions.

Every node is a frozen value that knows where it was written; a running step is addressed by
the child indices leading to it from the body's root (``node_at``).
"""

from __future__ import annotations

import difflib
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, Protocol

from ..sexpr import Atom, SList, to_text
from ..terms import ActionTemplate, Expr, Literal, Loc, Var, fmt


class Kind(StrEnum):
    """The construct families of Appendix C (the star is a separate flag)."""

    DO = "do"
    ALL = "do-all"
    ANY = "do-any"
    FIRST = "do-first"
    BEST = "do-best"
    REPEAT = "repeat"


CONSTRUCTS: dict[str, tuple[Kind, bool]] = {
    "do": (Kind.DO, False), "do*": (Kind.DO, True),
    "do-all": (Kind.ALL, False), "do*-all": (Kind.ALL, True),
    "do-any": (Kind.ANY, False), "do*-any": (Kind.ANY, True),
    "do-first": (Kind.FIRST, False), "do*-first": (Kind.FIRST, True),
    "do-best": (Kind.BEST, False), "do*-best": (Kind.BEST, True),
    "repeat": (Kind.REPEAT, False), "repeat*": (Kind.REPEAT, True),
}
MODIFIERS = (":while", ":until", ":when", ":unless")
SPECIAL = ("atomic", "assert", "retract", "wait")
WORDS = (*CONSTRUCTS, *SPECIAL)


@dataclass(frozen=True, slots=True)
class Mods:
    """A construct's modifiers; None where not given (``()`` is an empty, true, condition)."""

    while_: tuple | None = None
    until: tuple | None = None
    when: tuple | None = None
    unless: tuple | None = None

    def items(self) -> list[tuple[str, tuple]]:
        """(keyword, conditions) of the modifiers given, in the order :when :unless :while
        :until (the order they are checked in)."""
        pairs = ((":when", self.when), (":unless", self.unless), (":while", self.while_),
                 (":until", self.until))
        return [(k, v) for k, v in pairs if v is not None]


@dataclass(frozen=True, slots=True)
class Act:
    """An atomic action ``(*name arg ...)``: succeeds or fails as the world reports."""

    action: ActionTemplate
    loc: Loc | None = None

    def __str__(self) -> str:
        return str(self.action)


@dataclass(frozen=True, slots=True)
class ModelUpdate:
    """``(assert (FACT))`` or ``(retract (FACT))``: changes the agent's world model."""

    fact: Literal
    retract: bool = False
    loc: Loc | None = None

    def __str__(self) -> str:
        return f"({'retract' if self.retract else 'assert'} {self.fact})"


@dataclass(frozen=True, slots=True)
class Atomic:
    """``(atomic STEP ...)``: actions (and model updates) done together in one cycle, in
    order, with no condition checked between them; fails if any action fails."""

    steps: tuple  # Act | ModelUpdate
    loc: Loc | None = None

    def __str__(self) -> str:
        return "(atomic " + " ".join(str(s) for s in self.steps) + ")"


@dataclass(frozen=True, slots=True)
class Subgoal:
    """``(LITERAL)``: achieve a concept through the skill hierarchy."""

    literal: Literal
    loc: Loc | None = None

    def __str__(self) -> str:
        return str(self.literal)


@dataclass(frozen=True, slots=True)
class Wait:
    """``(wait COND ...)``: the thread stops here until the conditions hold."""

    conds: tuple
    loc: Loc | None = None

    def __str__(self) -> str:
        return "(wait " + " ".join(str(c) for c in self.conds) + ")"


@dataclass(frozen=True, slots=True)
class Branch:
    """One ``(CONDS STEP)`` of do-first, or ``(CONDS :utility EXPR [:reward EXPR] STEP)`` of
    do-best. ``utility``/``reward`` are expressions (None when not given)."""

    conds: tuple
    step: Any
    utility: object = None
    reward: object = None
    loc: Loc | None = None

    def __str__(self) -> str:
        conds = "(" + " ".join(str(c) for c in self.conds) + ")"
        util = f" :utility {fmt(self.utility)}" if self.utility is not None else ""
        return f"({conds}{util} {self.step})"


@dataclass(frozen=True, slots=True)
class Construct:
    """``(NAME MODS STEP ...)``; for do-first and do-best the steps are Branch values."""

    kind: Kind
    star: bool
    mods: Mods
    steps: tuple
    loc: Loc | None = None

    @property
    def name(self) -> str:
        """As written: ``do*-best``, ``repeat*``, ``do``."""
        if not self.star:
            return self.kind.value
        return "repeat*" if self.kind is Kind.REPEAT else "do*" + self.kind.value[2:]

    def __str__(self) -> str:
        first = children(self)[0]
        more = " ..." if len(self.steps) > 1 else ""
        text = f"({self.name} {first}{more})"
        return text if len(text) <= 60 else f"({self.name} ...)"


Step = Act | Atomic | Subgoal | ModelUpdate | Wait | Construct


def children(node: object) -> tuple:
    """The child steps of a node (a Branch's step for do-first/do-best)."""
    if isinstance(node, Construct):
        return tuple(s.step if isinstance(s, Branch) else s for s in node.steps)
    return ()


_USES: dict[int, tuple[object, frozenset]] = {}


def uses(node: object) -> frozenset:
    """The variables a step (with everything inside it) reads: in actions, subgoals, facts,
    conditions, utilities and rewards (cached per node)."""
    hit = _USES.get(id(node))
    if hit is not None and hit[0] is node:
        return hit[1]
    found: set = set()
    for _, n in walk_steps(node):
        if isinstance(n, Act):
            found |= n.action.variables()
        elif isinstance(n, Subgoal):
            found |= n.literal.variables()
        elif isinstance(n, ModelUpdate):
            found |= n.fact.variables()
        elif isinstance(n, Atomic):
            found |= set().union(*(uses(x) for x in n.steps))
        elif isinstance(n, Wait):
            found |= set().union(*(c.variables() for c in n.conds))
        elif isinstance(n, Construct):
            for _, conds in n.mods.items():
                found |= set().union(*(c.variables() for c in conds))
            for br in n.steps:
                if isinstance(br, Branch):
                    found |= set().union(*(c.variables() for c in br.conds))
                    for e in (br.utility, br.reward):
                        found |= _expr_vars(e)
    result = frozenset(found)
    _USES[id(node)] = (node, result)
    return result


def _expr_vars(e: object) -> set:
    if isinstance(e, Var):
        return {e}
    return e.variables() if isinstance(e, Expr) else set()


def node_at(root: object, at: tuple[int, ...]) -> object:
    """The step at address ``at`` below ``root``."""
    node = root
    for i in at:
        node = children(node)[i]
    return node


def walk_steps(root: object, at: tuple[int, ...] = ()):
    """Every (address, step) of a body, parents before children."""
    yield at, root
    for i, c in enumerate(children(root)):
        yield from walk_steps(c, (*at, i))


class PieceReader(Protocol):
    """What the body reader needs from the program parser (agents/lang/parser.py)."""

    def err(self, node: object, msg: str, severity: str = "error") -> None: ...

    def loc(self, node: object) -> Loc: ...

    def conditions(self, node: SList | None, tests: bool = True) -> list: ...

    def literal(self, node: object, what: str, allow_not: bool = True) -> Literal | None: ...

    def action(self, node: object) -> ActionTemplate | None: ...

    def expr(self, node: object) -> object: ...


def head_word(node: object) -> object:
    """The first item's value of a list node, or None."""
    if isinstance(node, SList) and node.items and isinstance(node.items[0], Atom):
        return node.items[0].value
    return None


class BodyReader:
    """Reads a ``:body`` into a step tree, reporting every problem through ``p.err``."""

    def __init__(self, p: PieceReader):
        self.p = p

    def step(self, node: object) -> Step | None:
        if not isinstance(node, SList) or not node.items:
            self.p.err(node, f"expected a step such as (*gas 10), (do ...) or (at-address ?self "
                       f"?ad), got {to_text(node)}")
            return None
        word = head_word(node)
        if isinstance(word, str) and word.startswith(":"):
            self.p.err(node, f"modifier {word} is misplaced: modifiers come right after a "
                       "construct's name, as in (do :while ((ready ?self)) STEP ...)")
            return None
        if isinstance(word, str) and word.startswith("*"):
            action = self.p.action(node)
            return None if action is None else Act(action, self.p.loc(node))
        if word in CONSTRUCTS:
            return self.construct(node, *CONSTRUCTS[word])
        if word in ("assert", "retract"):
            return self.update(node, word == "retract")
        if word == "atomic":
            return self.atomic(node)
        if word == "wait":
            return self.wait(node)
        if isinstance(word, str) and any(isinstance(x, SList) for x in node.items[1:]):
            close = difflib.get_close_matches(word, WORDS, n=1, cutoff=0.6)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            self.p.err(node.items[0], f"unknown construct '{word}'{hint}; constructs are "
                       f"{', '.join(CONSTRUCTS)}, atomic, assert, retract, wait")
            return None
        lit = self.p.literal(node, "subgoal", allow_not=False)
        return None if lit is None else Subgoal(lit, self.p.loc(node))

    def update(self, node: SList, retract: bool) -> ModelUpdate | None:
        word = "retract" if retract else "assert"
        if len(node.items) != 2:
            self.p.err(node, f"({word} (FACT)) takes exactly one fact, got "
                       f"{len(node.items) - 1} item(s)")
            return None
        lit = self.p.literal(node.items[1], f"{word}ed fact", allow_not=False)
        return None if lit is None else ModelUpdate(lit, retract, self.p.loc(node))

    def atomic(self, node: SList) -> Atomic | None:
        steps = []
        for item in node.items[1:]:
            word = head_word(item)
            if not (isinstance(word, str) and (word.startswith("*")
                                               or word in ("assert", "retract"))):
                self.p.err(item, f"(atomic ...) holds only actions (*name ...) and assert/"
                           f"retract, got {to_text(item)}")
                continue
            s = self.step(item)
            if s is not None:
                steps.append(s)
        if len(node.items) == 1:
            self.p.err(node, "(atomic ...) needs at least one action")
        return Atomic(tuple(steps), self.p.loc(node)) if steps else None

    def wait(self, node: SList) -> Wait | None:
        items = node.items[1:]
        if len(items) == 1 and isinstance(items[0], SList) and items[0].items \
                and isinstance(items[0].items[0], SList):
            items = items[0].items   # (wait ((c1) (c2))) as well as (wait (c1) (c2))
        if not items:
            self.p.err(node, "(wait COND ...) needs at least one condition")
            return None
        conds = self.p.conditions(SList(tuple(items), node.line, node.col))
        return Wait(tuple(conds), self.p.loc(node))

    def construct(self, node: SList, kind: Kind, star: bool) -> Construct | None:
        name = to_text(node.items[0])
        mods, rest = self.mods(node.items[1:], name)
        if not rest:
            self.p.err(node, f"({name} ...) has no steps")
            return None
        if kind in (Kind.FIRST, Kind.BEST):
            parts = [self.branch(item, name, kind is Kind.BEST) for item in rest]
        else:
            parts = [self.step(item) for item in rest]
        if any(s is None for s in parts):
            return None
        return Construct(kind, star, mods, tuple(parts), self.p.loc(node))

    def mods(self, items: tuple, name: str) -> tuple[Mods, tuple]:
        """The leading modifiers of a construct and the items after them."""
        found: dict[str, tuple] = {}
        i = 0
        while i < len(items) and isinstance(items[i], Atom) and isinstance(items[i].value, str) \
                and items[i].value.startswith(":"):
            key = items[i].value
            if key not in MODIFIERS:
                close = difflib.get_close_matches(key, MODIFIERS, n=1, cutoff=0.6)
                hint = f" (did you mean '{close[0]}'?)" if close else ""
                self.p.err(items[i], f"unknown modifier {key} in ({name} ...){hint}; "
                           f"modifiers are {' '.join(MODIFIERS)}")
            elif i + 1 >= len(items) or not isinstance(items[i + 1], SList):
                self.p.err(items[i], f"{key} needs a list of conditions after it, such as "
                           f"{key} ((clear ?x))")
            else:
                if key in found:
                    self.p.err(items[i], f"{key} given twice in ({name} ...)")
                found[key] = tuple(self.p.conditions(items[i + 1]))
            i += 2
        rest, skip = [], False
        for item in items[i:]:
            if isinstance(item, Atom) and isinstance(item.value, str) \
                    and item.value.startswith(":"):
                self.p.err(item, f"modifier {item.value} is misplaced: in ({name} ...) "
                           "modifiers come before the steps")
                skip = True   # its conditions are not a step
            elif skip:
                skip = False
            else:
                rest.append(item)
        return Mods(found.get(":while"), found.get(":until"), found.get(":when"),
                    found.get(":unless")), tuple(rest)

    def branch(self, node: object, name: str, best: bool) -> Branch | None:
        shape = "(CONDS :utility EXPR STEP)" if best else "(CONDS STEP)"
        if not (isinstance(node, SList) and len(node.items) >= 2
                and isinstance(node.items[0], SList)):
            self.p.err(node, f"each alternative of ({name} ...) is {shape}, where CONDS is a "
                       f"list of conditions such as ((clear ?x)), got {to_text(node)}")
            return None
        conds = tuple(self.p.conditions(node.items[0]))
        rest = list(node.items[1:])
        keys: dict[str, object] = {}
        while len(rest) >= 2 and isinstance(rest[0], Atom) and isinstance(rest[0].value, str) \
                and rest[0].value.startswith(":"):
            key, value = rest[0], rest[1]
            rest = rest[2:]
            if key.value in (":utility", ":reward") and best:
                keys[key.value] = self.p.expr(value)
            elif key.value in MODIFIERS:
                self.p.err(key, f"modifier {key.value} is misplaced: put it after the "
                           f"construct's name, ({name} {key.value} (...) ...)")
            else:
                allowed = ":utility, :reward" if best else "none"
                self.p.err(key, f"{key.value} is not allowed in an alternative of ({name} ...) "
                           f"(allowed: {allowed})")
        if best and ":utility" not in keys:
            self.p.err(node, f"alternative of ({name} ...) has no :utility; write {shape}")
        if len(rest) != 1:
            self.p.err(node, f"alternative of ({name} ...) needs exactly one step after its "
                       f"conditions, got {len(rest)}: write {shape}, wrapping several steps "
                       "in (do ...)")
            return None
        step = self.step(rest[0])
        if step is None or (best and keys.get(":utility") is None):
            return None
        return Branch(conds, step, keys.get(":utility"), keys.get(":reward"), self.p.loc(node))
