"""Compile rules into Python functions: nested loops over indexed relations.

A rule is compiled in variants. The full variant joins every element; a *driver* variant first
binds the variables of one element from a given list (the tuples inserted into or deleted from
its relation, or, for a negated element, the keys whose negation became true or false) and
joins the rest; the head variant binds the head from given facts (is this fact still
derivable?). Each element reads its own store from ``S`` (the current store, or a view of the
previous state), so one function serves every incremental update.

Join order is chosen by selectivity with the relations' sizes when the variant is first used
(``plan``): tests and negations as soon as their variables are bound, then the element with the
fewest expected matches per binding (size over distinct keys on the bound positions). A plan is
made again when a relation it counted on has grown or shrunk a lot.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..core.store import key_getter
from ..core.terms import Expr, Var
from .rules import Rule

_PYOP = {"<": "<", "<=": "<=", ">": ">", ">=": ">=", "=": "==", "<>": "!=", "+": "+", "-": "-",
         "*": "*", "/": "/", "mod": "%"}
_FUNCS = {"abs": "abs", "min": "min", "max": "max", "sqrt": "_sqrt"}
HEAD = -1  # driver: the head
_NS = {"_ONE": (0,), "_ERRS": (ArithmeticError, TypeError, ValueError), "_sqrt": math.sqrt}


class Estimator:
    """Expected matches of an element per binding, from the current stores (memoised)."""

    def __init__(self, edb, idb, check: bool = True):
        self.stores = (idb, edb)
        self.memo: dict = {}
        self.check = check  # whether variants look for sizes that drifted since they were planned

    def fanout(self, rel: object, percept: bool, positions: tuple, arity: int) -> float:
        store = self.stores[percept]
        n = len(store.get(rel))
        if not positions:
            return float(n)
        if len(positions) == arity:
            return min(0.5, float(n))
        key = (rel, positions)
        d = self.memo.get(key)
        if d is None:
            if store.has_index(rel, positions):
                d = len(store.index(rel, positions))
            else:
                d = len(set(map(key_getter(positions), store.get(rel))))
            self.memo[key] = d
        return n / max(d, 1)


def plan(rule: Rule, driver: int | None, est: Estimator) -> tuple:
    """Steps ("pos"|"neg", element) and ("test", k) in join order after the driver."""
    bound = _driver_vars(rule, driver)
    pos = [j for j, e in enumerate(rule.elems) if not e.negated and j != driver]
    negs = [j for j, e in enumerate(rule.elems) if e.negated and j != driver]
    tests = list(range(len(rule.tests)))
    steps: list[tuple] = []
    while pos or negs or tests:
        ready = [("test", k) for k in tests if rule.tests[k].variables() <= bound]
        ready += [("neg", j) for j in negs
                  if rule.elems[j].variables() & rule.outer <= bound]
        if ready:
            steps += ready
            tests = [k for k in tests if ("test", k) not in ready]
            negs = [j for j in negs if ("neg", j) not in ready]
            continue
        if not pos:  # variables bound nowhere: the checker prevents it; keep written order
            steps += [("test", k) for k in tests] + [("neg", j) for j in negs]
            break

        best = min(pos, key=lambda j, bound=bound: _cost(rule, j, bound, est))
        pos.remove(best)
        steps.append(("pos", best))
        bound |= rule.elems[best].variables()
    return tuple(steps)


def _cost(rule: Rule, j: int, bound: set[Var], est: Estimator) -> tuple:
    """Expected matches of element ``j`` per binding of ``bound`` (ties: written order)."""
    e = rule.elems[j]
    known = tuple(p for p, a in enumerate(e.args) if not isinstance(a, Var) or a in bound)
    return (est.fanout(e.rel, e.percept, known, len(e.args)), j)


def _driver_vars(rule: Rule, driver: int | None) -> set[Var]:
    if driver is None:
        return set()
    if driver == HEAD:
        return {a for a in rule.head if isinstance(a, Var)}
    e = rule.elems[driver]
    if e.negated:
        return {e.args[p] for p in rule.negation(driver).keys if isinstance(e.args[p], Var)}
    return e.variables()


class _Gen:
    def __init__(self, rule: Rule, driver: int | None):
        self.rule = rule
        self.driver = driver
        self.names: dict[Var, str] = {}
        self.lines: list[str] = []
        self.setup: list[str] = []
        self.depth = 1

    def var(self, v: Var) -> str:
        if v not in self.names:
            self.names[v] = f"v{len(self.names)}"
        return self.names[v]

    def emit(self, line: str) -> None:
        self.lines.append("    " * self.depth + line)

    def value(self, term: object) -> str:
        if isinstance(term, Var):
            return self.var(term)
        if isinstance(term, Expr):
            return self.expr(term)
        return repr(term)

    def expr(self, e: Expr) -> str:
        args = [self.value(a) for a in e.args]
        if e.op in _FUNCS:
            return f"{_FUNCS[e.op]}({', '.join(args)})"
        if e.op in ("and", "or"):
            return "(" + f" {e.op} ".join(args) + ")"
        if e.op == "not":
            return f"(not {args[0]})"
        if e.op == "-" and len(args) == 1:
            return f"(-{args[0]})"
        return "(" + f" {_PYOP[e.op]} ".join(args) + ")"

    def bind_or_check(self, src: str, term: object, bound: set[Var]) -> None:
        if isinstance(term, Var) and term not in bound:
            self.emit(f"{self.var(term)} = {src}")
            bound.add(term)
        else:
            self.emit(f"if {src} != {self.value(term)}: continue")

    def build(self, steps: tuple) -> str:
        rule, bound = self.rule, set()
        if self.driver is None:
            self.emit("for _once in _ONE:")
        else:
            self.emit("for _d in DRV:")
        self.depth += 1
        if self.driver == HEAD:
            for p, a in enumerate(rule.head):
                self.bind_or_check(f"_d[{p}]", a, bound)
        elif self.driver is not None:
            e = rule.elems[self.driver]
            if e.negated:
                for k, p in enumerate(rule.negation(self.driver).keys):
                    if isinstance(e.args[p], Var):
                        self.bind_or_check(f"_d[{k}]", e.args[p], bound)
            else:
                for p, a in enumerate(e.args):
                    self.bind_or_check(f"_d[{p}]", a, bound)
        for kind, j in steps:
            if kind == "test":
                self.emit("try:")
                self.emit(f"    if not {self.expr(rule.tests[j].expr)}: continue")
                self.emit("except _ERRS: continue")
            elif kind == "neg":
                self.negation(j, bound)
            else:
                self.positive(j, bound)
        if self.driver == HEAD:
            self.emit("_out(_d)")
        else:
            head = ", ".join(self.value(a) for a in rule.head)
            self.emit(f"_out(({head}{',' if len(rule.head) == 1 else ''}))")
        setup = "".join(f"    {s}\n" for s in self.setup)
        return f"def _rule(S, DRV, _out):\n{setup}" + "\n".join(self.lines) + "\n"

    def _key(self, args: tuple, pos: list[int]) -> str:
        return "(" + "".join(self.value(args[p]) + ", " for p in pos) + ")"

    def positive(self, j: int, bound: set[Var]) -> None:
        e = self.rule.elems[j]
        pos = [p for p, a in enumerate(e.args) if not isinstance(a, Var) or a in bound]
        if len(pos) == len(e.args):
            self.setup.append(f"r{j} = S[{j}].get({e.rel!r})")
            self.emit(f"if {self._key(e.args, pos)} not in r{j}: continue")
            return
        if pos:
            self.setup.append(f"x{j} = S[{j}].index({e.rel!r}, {tuple(pos)!r})")
            self.emit(f"for t{j} in x{j}.get({self._key(e.args, pos)}, ()):")
        else:
            self.setup.append(f"r{j} = S[{j}].get({e.rel!r})")
            self.emit(f"for t{j} in r{j}:")
        self.depth += 1
        for p, a in enumerate(e.args):
            if p not in pos:
                self.bind_or_check(f"t{j}[{p}]", a, bound)

    def negation(self, j: int, bound: set[Var]) -> None:
        e = self.rule.elems[j]
        pos = [p for p, a in enumerate(e.args) if not isinstance(a, Var) or a in bound]
        rest = [p for p in range(len(e.args)) if p not in pos]
        if not rest:
            self.setup.append(f"r{j} = S[{j}].get({e.rel!r})")
            self.emit(f"if {self._key(e.args, pos)} in r{j}: continue")
            return
        if pos:
            self.setup.append(f"x{j} = S[{j}].index({e.rel!r}, {tuple(pos)!r})")
            seq = f"x{j}.get({self._key(e.args, pos)}, ())"
        else:
            self.setup.append(f"r{j} = S[{j}].get({e.rel!r})")
            seq = f"r{j}"
        first: dict[Var, int] = {}
        conds = []
        for p in rest:
            a = e.args[p]
            if a in first:
                conds.append(f"t[{p}] == t[{first[a]}]")
            else:
                first[a] = p
        if conds:
            self.emit(f"if any(1 for t in {seq} if {' and '.join(conds)}): continue")
        else:
            self.emit(f"if {seq}: continue")


def compile_plan(rule: Rule, driver: int | None, steps: tuple) -> Callable:
    """Python function ``rule(S, DRV, out)`` calling ``out(head tuple)`` once per derivation."""
    source = _Gen(rule, driver).build(steps)
    ns = dict(_NS)
    name = f"<concept {rule.label} driver {driver}>"
    exec(compile(source, name, "exec"), ns)  # noqa: S102
    fn = ns["_rule"]
    fn.source = source
    return fn


class Variant:
    """One variant of a rule, planned on first use and planned again when a relation it reads
    has changed size by more than a factor of 4 (and 32 tuples) since (looked at when the
    Estimator says so: every run from scratch and every eighth run)."""

    __slots__ = ("rule", "driver", "fn", "sizes", "cache", "reads")

    def __init__(self, rule: Rule, driver: int | None):
        self.rule = rule
        self.driver = driver
        self.fn: Callable | None = None
        self.sizes: list = []
        self.cache: dict[tuple, Callable] = {}
        self.reads = [(e.percept, e.rel) for j, e in enumerate(rule.elems)
                      if j != driver and not e.negated]

    def get(self, est: Estimator) -> Callable:
        """The compiled function, planned again if the sizes it was planned for drifted."""
        if self.fn is not None and not est.check:
            return self.fn
        sizes = self._sizes(est)
        if self.fn is None or any(max(a, b) > 4 * min(a, b) + 32
                                  for a, b in zip(sizes, self.sizes, strict=True)):
            steps = plan(self.rule, self.driver, est)
            fn = self.cache.get(steps)
            if fn is None:
                fn = self.cache[steps] = compile_plan(self.rule, self.driver, steps)
            self.fn, self.sizes = fn, sizes
        return self.fn

    def _sizes(self, est: Estimator) -> list:
        stores = est.stores
        return [len(stores[p].get(rel)) for p, rel in self.reads]


def variants(rule: Rule) -> dict:
    """Lazily planned variants: None (full), HEAD, and one per element."""
    return {d: Variant(rule, d) for d in (None, HEAD, *range(len(rule.elems)))}
