"""Parsing the pieces of clauses: percept patterns, tests, expressions and actions.

A mixin for ``Parser``: it needs ``self.err(node, msg)`` and ``self.loc(node)``.
"""

from __future__ import annotations

import difflib

from ..core.arith import BOOL_OPS, LOGIC, OPS, check_call
from ..core.sexpr import Atom, SList, to_text
from ..core.terms import ActionTemplate, Expr, PerceptPattern, Test, Var


class PieceParser:
    """Percept patterns, tests, expressions and actions."""

    def items(self, node: Atom | SList | None, form: str) -> tuple:
        """The items of a list a clause key takes (none when absent); an atom where the list
        should be is an error at its place, saying the ``form`` of an item."""
        if node is None:
            return ()
        if isinstance(node, SList):
            return node.items
        self.err(node, f"expected a list of {form} in parentheses, got {to_text(node)}")
        return ()

    def patterns(self, node: SList | None) -> tuple[PerceptPattern, ...]:
        out = []
        for item in self.items(node, "percept patterns (type ?id attr ?value ...)"):
            if not (isinstance(item, SList) and len(item.items) >= 2
                    and all(isinstance(x, Atom) for x in item.items)):
                self.err(item, f"expected a percept pattern (type id attr value ...), got "
                         f"{to_text(item)}")
                continue
            vals = [x.value for x in item.items]
            if not isinstance(vals[0], str):
                self.err(item, f"percept type must be a symbol, got {to_text(item.items[0])}")
                continue
            if len(vals) % 2:
                self.err(item.items[-1], f"attribute {to_text(item.items[-1])} in {to_text(item)} "
                         "has no value")
                continue
            attrs = tuple((vals[i], vals[i + 1]) for i in range(2, len(vals), 2))
            bad = [a for a, _ in attrs if not isinstance(a, str) or isinstance(a, Var)]
            if bad:
                self.err(item, f"attribute names must be symbols in {to_text(item)}")
                continue
            out.append(PerceptPattern(vals[0], vals[1], attrs, self.loc(item)))
        return tuple(out)

    def tests(self, node: SList | None) -> tuple[Test, ...]:
        return tuple(t for t in (self.test(i) for i in self.items(node, "tests (< ?x 3)"))
                     if t is not None)

    def test(self, node: object) -> Test | None:
        e = self.expr(node)
        if e is None:
            return None
        if not isinstance(e, Expr):
            self.err(node, f"a test must be a call such as (< ?x 5), got {to_text(node)}")
            return None
        return Test(e, self.loc(node))

    def expr(self, node: object) -> object:
        if isinstance(node, Atom):
            return node.value
        if not node.items or not isinstance(node.items[0], Atom):
            self.err(node, f"expected (operator arg ...), got {to_text(node)}")
            return None
        op = node.items[0].value
        args = [self.expr(a) for a in node.items[1:]]
        msg = check_call(op, len(args)) if isinstance(op, str) else f"bad operator {op}"
        if msg:
            self.err(node, msg + suggest(op, list(OPS) + list(LOGIC)))
            return None
        return None if any(a is None for a in args) else Expr(op, tuple(args))

    def action(self, node: object) -> ActionTemplate | None:
        if not (isinstance(node, SList) and node.items and isinstance(node.items[0], Atom)
                and isinstance(node.items[0].value, str)):
            self.err(node, f"expected an action (*name arg ...), got {to_text(node)}")
            return None
        name = node.items[0].value
        if not name.startswith("*"):
            self.err(node, f"action names start with '*' (such as *gas), got {name}")
            return None
        args = [self.expr(a) for a in node.items[1:]]
        if any(a is None for a in args):
            return None
        for a, n in zip(args, node.items[1:], strict=True):
            if isinstance(a, Expr) and _is_bool(a):
                self.err(n, f"action argument {a} is a truth value; actions take numbers/symbols")
                return None
        return ActionTemplate(name, tuple(args), self.loc(node))


def _is_bool(e: Expr) -> bool:
    return e.op in BOOL_OPS


def op_name(node: object) -> object:
    if isinstance(node, SList) and node.items and isinstance(node.items[0], Atom):
        return node.items[0].value
    return None


def suggest(name: object, known) -> str:
    if not isinstance(name, str):
        return ""
    close = difflib.get_close_matches(name, list(known), n=1, cutoff=0.75)
    return f" (did you mean '{close[0]}'?)" if close else ""
