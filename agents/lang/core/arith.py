"""Test and arithmetic operators (seed 000, Table 2 :tests) compiled to Python closures.

Every expression compiles once; the closure reads variable values from ``env[key]``, where
``key`` is a slot number (list environments) or the Var itself (dict environments).
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable

from .errors import EvalError
from .terms import Expr, Var


def _sub(*xs: float) -> float:
    return -xs[0] if len(xs) == 1 else xs[0] - sum(xs[1:])


def _add(*xs: float) -> float:
    total = xs[0]
    for x in xs[1:]:
        total = total + x
    return total


def _mul(*xs: float) -> float:
    total = xs[0]
    for x in xs[1:]:
        total = total * x
    return total


# name -> (function, min arity, max arity or None); comparisons return bool.
OPS: dict[str, tuple[Callable, int, int | None]] = {
    "<": (operator.lt, 2, 2), "<=": (operator.le, 2, 2), ">": (operator.gt, 2, 2),
    ">=": (operator.ge, 2, 2), "=": (operator.eq, 2, 2), "<>": (operator.ne, 2, 2),
    "+": (_add, 1, None), "-": (_sub, 1, None), "*": (_mul, 1, None), "/": (operator.truediv, 2, 2),
    "abs": (abs, 1, 1), "min": (min, 1, None), "max": (max, 1, None), "sqrt": (math.sqrt, 1, 1),
    "mod": (operator.mod, 2, 2),
}
LOGIC = {"and", "or", "not"}
BOOL_OPS = {"<", "<=", ">", ">=", "=", "<>"} | LOGIC
_ERRORS = (ArithmeticError, TypeError, ValueError)


def check_call(op: str, nargs: int) -> str | None:
    """Return a message if ``(op ...)`` with ``nargs`` arguments is not a valid call, else None."""
    if op in LOGIC:
        if op == "not" and nargs != 1:
            return f"'not' in a test takes 1 argument, got {nargs}"
        return None if nargs >= 1 else f"'{op}' takes at least 1 argument"
    if op not in OPS:
        known = " ".join(sorted(OPS) + sorted(LOGIC))
        return f"unknown operator '{op}' (known: {known})"
    _, lo, hi = OPS[op]
    if nargs < lo or (hi is not None and nargs > hi):
        want = f"{lo}" if lo == hi else f"at least {lo}" if hi is None else f"{lo}..{hi}"
        return f"'{op}' takes {want} argument(s), got {nargs}"
    return None


def compile_expr(term: object, key: Callable[[Var], object]) -> Callable[[object], object]:
    """Closure computing ``term`` from an environment; raises the Python error on failure."""
    if isinstance(term, Var):
        k = key(term)
        return lambda env: env[k]
    if not isinstance(term, Expr):
        return lambda env: term
    subs = [compile_expr(a, key) for a in term.args]
    if term.op == "and":
        return lambda env: all(s(env) for s in subs)
    if term.op == "or":
        return lambda env: any(s(env) for s in subs)
    if term.op == "not":
        s0 = subs[0]
        return lambda env: not s0(env)
    fn = OPS[term.op][0]
    if len(subs) == 2:
        a, b = subs
        return lambda env: fn(a(env), b(env))
    if len(subs) == 1:
        a = subs[0]
        return lambda env: fn(a(env))
    return lambda env: fn(*[s(env) for s in subs])


def compile_test(expr: Expr, key: Callable[[Var], object]) -> Callable[[object], bool]:
    """Closure returning True when the test holds; evaluation errors make the test fail."""
    f = compile_expr(expr, key)

    def test(env: object) -> bool:
        try:
            return bool(f(env))
        except _ERRORS:
            return False
    return test


def evaluate(term: object, bindings: dict) -> object:
    """Value of ``term`` under dict ``bindings``; raises EvalError naming the expression."""
    try:
        value = _value(term, bindings)
    except KeyError as exc:
        raise EvalError(f"{term}: variable {exc.args[0]} is unbound") from None
    except _ERRORS as exc:
        raise EvalError(f"{term}: {exc}") from None
    if isinstance(value, bool):
        raise EvalError(f"{term}: gives a truth value, not a number or symbol")
    return value


def _value(term: object, env: dict) -> object:
    """``term`` under ``env``, as ``compile_expr(term, key)(env)`` computes it with ``key`` the
    identity (an expression evaluated once is cheaper walked than compiled)."""
    if isinstance(term, Var):
        return env[term]
    if not isinstance(term, Expr):
        return term
    op, args = term.op, term.args
    if op == "and":
        return all(_value(a, env) for a in args)
    if op == "or":
        return any(_value(a, env) for a in args)
    if op == "not":
        return not _value(args[0], env)
    return OPS[op][0](*[_value(a, env) for a in args])
