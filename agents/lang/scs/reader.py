"""Reading a skill's ``:body`` into the step tree of agents/lang/scs/syntax.py, every problem
reported through the program parser at file:line:col (agents/lang/reading/parser.py asks
the mechanism that reads bodies, Scs.read_body, which calls ``BodyReader``): unknown
constructs (with "did you mean"), misplaced or unknown modifiers, alternatives of the wrong
shape, a do-best alternative without ``:utility``, conditions of neither form.

CONDS (of do-first and do-best alternatives, of ``:while``/``:until``/``:when``/``:unless``)
is one condition, ``(lamp-on L1)`` (seed 002's ``K1 -> S1`` written directly), or a list of
them, ``((lamp-on L1) (not (busy ?j)))``, with ``()`` always true: a condition starts with a
symbol, a list of conditions with a list, so the two are read without ambiguity."""

from __future__ import annotations

import difflib
from typing import Protocol

from ..core.sexpr import Atom, SList, to_text
from ..core.terms import ActionTemplate, Literal, Loc
from .syntax import (
    CONSTRUCTS,
    MODIFIERS,
    WORDS,
    Act,
    Atomic,
    Branch,
    Construct,
    Kind,
    ModelUpdate,
    Mods,
    Step,
    Subgoal,
    Wait,
)


class PieceReader(Protocol):
    """What the body reader needs from the program parser (agents/lang/reading/parser.py)."""

    def err(self, node: object, msg: str, severity: str = "error") -> None: ...

    def loc(self, node: object) -> Loc: ...

    def conditions(self, node: SList | None, tests: bool = True) -> list: ...

    def literal(self, node: object, what: str, allow_not: bool = True) -> Literal | None: ...

    def action(self, node: object) -> ActionTemplate | None: ...

    def expr(self, node: object) -> object: ...


CONDS_FORMS = ("one condition such as (lamp-on L1), a list of conditions such as "
               "((lamp-on L1) (clear ?x)), or () for always true")


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
        """``(wait COND ...)``, or ``(wait CONDS)``: (wait (c1) (c2)), (wait ((c1) (c2))),
        (wait (c1)) and (wait ()), always true, all read."""
        items = node.items[1:]
        if not items:
            self.p.err(node, f"(wait CONDS) needs its conditions: {CONDS_FORMS}")
            return None
        if len(items) == 1:
            conds = self.conds(items[0], "(wait ...)")
        else:
            conds = self.conds(SList(tuple(items), node.line, node.col), "(wait ...)")
        return Wait(conds, self.p.loc(node))

    def conds(self, node: object, where: str) -> tuple:
        """CONDS (see the top): one condition, a list of them, or () (always true); where
        neither is found, the error names the forms expected."""
        if not isinstance(node, SList):
            self.p.err(node, f"{where}: expected CONDS, {CONDS_FORMS}; got {to_text(node)}")
            return ()
        if node.items and isinstance(node.items[0], Atom):
            return tuple(self.p.conditions(SList((node,), node.line, node.col)))
        good = []
        for item in node.items:
            if isinstance(item, SList) and item.items and isinstance(item.items[0], Atom):
                good.append(item)
            else:
                self.p.err(item, f"{where}: in a list of conditions each one is a condition "
                           f"such as (lamp-on L1) or (not (clear ?x)), got {to_text(item)} "
                           f"(CONDS is {CONDS_FORMS})")
        return tuple(self.p.conditions(SList(tuple(good), node.line, node.col)))

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
                got = to_text(items[i + 1]) if i + 1 < len(items) else "nothing"
                self.p.err(items[i], f"{key} in ({name} ...) needs CONDS after it: "
                           f"{CONDS_FORMS}; got {got}")
            else:
                if key in found:
                    self.p.err(items[i], f"{key} given twice in ({name} ...)")
                found[key] = self.conds(items[i + 1], f"{key} of ({name} ...)")
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
            self.p.err(node, f"each alternative of ({name} ...) is {shape}, where CONDS is "
                       f"{CONDS_FORMS}; got {to_text(node)}")
            return None
        conds = self.conds(node.items[0], f"the conditions of an alternative of ({name} ...)")
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
