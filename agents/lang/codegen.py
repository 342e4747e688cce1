"""Compile concept clauses into Python functions (nested loops over indexed percepts and facts).

Join order is chosen statically and greedily: tests and negations as soon as their variables are
bound, then the most constrained positive element (bound id / bound arguments first). For
semi-naive evaluation of recursive concepts one positive literal can read the delta store instead
of the full store (seed 000, "Inference and Execution Mechanisms": bottom-up to fixpoint).
"""

from __future__ import annotations

import math
from collections.abc import Callable

from .program import ConceptClause
from .store import MISSING
from .terms import Expr, Literal, PerceptPattern, Test, Var

_PYOP = {"<": "<", "<=": "<=", ">": ">", ">=": ">=", "=": "==", "<>": "!=", "+": "+", "-": "-",
         "*": "*", "/": "/", "mod": "%"}
_FUNCS = {"abs": "abs", "min": "min", "max": "max", "sqrt": "_sqrt"}


class _Gen:
    def __init__(self, clause: ConceptClause, delta: int | None):
        self.clause = clause
        self.delta = delta
        self.names: dict[Var, str] = {}
        self.lines: list[str] = []
        self.setup: list[str] = []
        self.depth = 1
        self.counter = 0

    def var(self, v: Var) -> str:
        if v not in self.names:
            self.names[v] = f"v{len(self.names)}"
        return self.names[v]

    def emit(self, line: str) -> None:
        self.lines.append("    " * self.depth + line)

    def value(self, term: object, bound: set[Var]) -> str:
        if isinstance(term, Var):
            return self.var(term)
        if isinstance(term, Expr):
            return self.expr(term)
        return repr(term)

    def expr(self, e: Expr) -> str:
        args = [self.value(a, set()) for a in e.args]
        if e.op in _FUNCS:
            return f"{_FUNCS[e.op]}({', '.join(args)})"
        if e.op in ("and", "or"):
            return "(" + f" {e.op} ".join(args) + ")"
        if e.op == "not":
            return f"(not {args[0]})"
        if e.op == "-" and len(args) == 1:
            return f"(-{args[0]})"
        return "(" + f" {_PYOP[e.op]} ".join(args) + ")"

    # -- ordering ----------------------------------------------------------------------------
    def order(self) -> list:
        c = self.clause
        positives: list = [*c.percepts, *(r for r in c.relations if not r.negated)]
        negs = [r for r in c.relations if r.negated]
        tests = list(c.tests)
        outer: set[Var] = set(c.head.variables())
        for x in positives + tests:
            outer |= x.variables()
        bound: set[Var] = set()
        plan: list = []
        delta_lit = None if self.delta is None else c.relations[self.delta]
        while positives or negs or tests:
            ready = [t for t in tests if t.variables() <= bound]
            ready += [n for n in negs if (n.variables() & outer) <= bound]
            if ready:
                for x in ready:
                    plan.append(x)
                    (tests if isinstance(x, Test) else negs).remove(x)
                continue
            if not positives:  # unbound test/negation vars: checker prevents; keep order
                plan += tests + negs
                break
            best = max(positives, key=lambda x: (x is delta_lit, _score(x, bound)))
            positives.remove(best)
            plan.append(best)
            bound |= best.variables()
        return plan

    # -- code ----------------------------------------------------------------------------------
    def build(self) -> str:
        self.emit("for _once in _ONE:")
        self.depth += 1
        bound: set[Var] = set()
        for x in self.order():
            if isinstance(x, PerceptPattern):
                self.percept(x, bound)
            elif isinstance(x, Test):
                self.emit("try:")
                self.emit(f"    if not {self.expr(x.expr)}: continue")
                self.emit("except _ERRS: continue")
            elif x.negated:
                self.negation(x, bound)
            else:
                self.fact(x, bound)
        head = ", ".join(self.value(a, bound) for a in self.clause.head.args)
        self.emit(f"_out(({head}{',' if len(self.clause.head.args) == 1 else ''}))")
        body = "\n".join(self.lines)
        setup = "\n".join("    " + s for s in self.setup)
        return f"def _rule(P, F, D, _out):\n{setup}\n{body}\n"

    def new(self, prefix: str) -> str:
        self.counter += 1
        return f"{prefix}{self.counter}"

    def bind_or_check(self, src: str, term: object, bound: set[Var]) -> None:
        if isinstance(term, Var) and term not in bound:
            self.emit(f"{self.var(term)} = {src}")
            bound.add(term)
        else:
            self.emit(f"if {src} != {self.value(term, bound)}: continue")

    def percept(self, p: PerceptPattern, bound: set[Var]) -> None:
        it = self.new("p")
        src = self.new("s")
        id_bound = not isinstance(p.id, Var) or p.id in bound
        attr_b = next(((a, t) for a, t in p.attrs if not isinstance(t, Var) or t in bound), None)
        if id_bound:
            self.setup.append(f"{src} = P.by_id")
            seq = f"{src}.get(({p.type!r}, {self.value(p.id, bound)}), ())"
        elif attr_b is not None:
            self.setup.append(f"{src} = P.attr_index({p.type!r}, {attr_b[0]!r})")
            seq = f"{src}.get({self.value(attr_b[1], bound)}, ())"
        else:
            self.setup.append(f"{src} = P.by_type.get({p.type!r}, ())")
            seq = src
        self.emit(f"for {it} in {seq}:")
        self.depth += 1
        if not id_bound:
            self.bind_or_check(f"{it}.id", p.id, bound)
        if p.attrs:
            self.emit(f"m = {it}._map")
        for a, t in p.attrs:
            if isinstance(t, Var) and t not in bound:
                self.emit(f"{self.var(t)} = m.get({a!r}, _MISSING)")
                self.emit(f"if {self.var(t)} is _MISSING: continue")
                bound.add(t)
            elif attr_b is None or (a, t) != attr_b or id_bound:
                self.emit(f"if m.get({a!r}, _MISSING) != {self.value(t, bound)}: continue")

    def _lookup(self, lit: Literal, bound: set[Var], store: str) -> tuple[str, list[int]]:
        pos = [i for i, a in enumerate(lit.args) if not isinstance(a, Var) or a in bound]
        src = self.new("f")
        if pos:
            self.setup.append(f"{src} = {store}.index({lit.pred!r}, {tuple(pos)!r})")
            key = ", ".join(self.value(lit.args[i], bound) for i in pos)
            return f"{src}.get(({key},), ())", pos
        self.setup.append(f"{src} = {store}.get({lit.pred!r})")
        return src, pos

    def fact(self, lit: Literal, bound: set[Var]) -> None:
        store = "D" if self.delta is not None and lit is self.clause.relations[self.delta] else "F"
        seq, pos = self._lookup(lit, bound, store)
        it = self.new("t")
        self.emit(f"for {it} in {seq}:")
        self.depth += 1
        for i, a in enumerate(lit.args):
            if i not in pos:
                self.bind_or_check(f"{it}[{i}]", a, bound)

    def negation(self, lit: Literal, bound: set[Var]) -> None:
        seq, pos = self._lookup(lit, bound, "F")
        rest = [i for i in range(len(lit.args)) if i not in pos]
        first: dict[Var, int] = {}
        conds = []
        for i in rest:
            a = lit.args[i]
            if a in first:
                conds.append(f"t[{i}] == t[{first[a]}]")
            else:
                first[a] = i
        if not conds:
            self.emit(f"if {seq}: continue")
        else:
            self.emit(f"if any(1 for t in {seq} if {' and '.join(conds)}): continue")


def _score(x: object, bound: set[Var]) -> tuple:
    if isinstance(x, PerceptPattern):
        if not isinstance(x.id, Var) or x.id in bound:
            return (3, 0)
        nb = sum(1 for _, t in x.attrs if not isinstance(t, Var) or t in bound)
        return (2 if nb else 1, nb)
    nb = sum(1 for a in x.args if not isinstance(a, Var) or a in bound)
    if x.args and nb == len(x.args):
        return (4, 0)
    return (2 if nb else 0, nb)


_NS = {"_ONE": (0,), "_ERRS": (ArithmeticError, TypeError, ValueError), "_MISSING": MISSING,
       "_sqrt": math.sqrt}


def compile_clause(clause: ConceptClause, delta: int | None = None) -> Callable:
    """Python function ``rule(P, F, D, out)`` calling ``out(args)`` for every match."""
    source = _Gen(clause, delta).build()
    ns = dict(_NS)
    exec(compile(source, f"<concept {clause.head} #{clause.index}>", "exec"), ns)  # noqa: S102
    fn = ns["_rule"]
    fn.source = source
    return fn
