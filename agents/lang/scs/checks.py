"""Semantic checks of skill bodies, reported at file:line:col with the program's other
diagnostics (agents/lang/reading/checks.py calls ``BodyChecks``): subgoals naming an undefined
concept, the wrong arity or a concept no skill achieves, unknown constructs, actions a
program with a (resources ...) section does not list there, variables bound nowhere (a body
step sees the skill's head, :percepts, :start and :requires bindings, and those of the
:when/:while conditions of the constructs around it and of its do-first/do-best
alternative), and facts asserted with different arities. Asserted and retracted predicates
are the world model's: each is defined by its first assert (a concept of that name, if
any, has its instances joined with them)."""

from __future__ import annotations

import difflib
from collections.abc import Iterable
from typing import Protocol

from ..core.program import Skill
from ..core.terms import Literal, Loc, Test, Var
from .syntax import (
    WORDS,
    Act,
    Atomic,
    Branch,
    Construct,
    ModelUpdate,
    Subgoal,
    Wait,
    expr_vars,
    walk_steps,
)
from .unreached import cut_off


class CheckerLike(Protocol):
    """What the body checks need from agents/lang/reading/checks.py's Checker."""

    arity: dict[str, int]

    def err(self, loc: Loc | None, msg: str, severity: str = "error") -> None: ...

    def use(self, lit: Literal, what: str) -> bool: ...

    def unbound(self, vs: set[Var], loc: Loc | None, where: str, hint: str,
                bound: set[Var] = ...) -> None: ...


def model_facts(skills: Iterable[Skill]) -> list[ModelUpdate]:
    """Every assert/retract in the bodies of ``skills``, in program order."""
    out = []
    for s in skills:
        if s.body is not None:
            for _, node in walk_steps(s.body):
                parts = node.steps if isinstance(node, Atomic) else (node,)
                out += [p for p in parts if isinstance(p, ModelUpdate)]
    return out


def known_actions(resources: dict | None) -> set[str]:
    """The actions a program declares in its (resources ...) section (empty without one:
    then any action name is accepted)."""
    return set(resources or ())


class BodyChecks:
    """Checks one skill's body against the program."""

    HINT = "bind it in the head, :percepts, :start, :requires or an enclosing condition"

    def __init__(self, checker: CheckerLike, skills: list[Skill], actions: set[str]):
        self.c = checker
        self.achievable = {s.head.pred for s in skills}
        self.actions = actions

    def check(self, s: Skill, bound: set[Var]) -> None:
        self.skill = s
        self.step(s.body, set(bound))
        for update, never in cut_off(s):
            self.c.err(update.loc, f"{update} makes the goal {s.head} of skill {s.name} "
                       f"true: the body ends when its goal holds (from the next cycle), so "
                       f"these steps after it never run: {', '.join(map(str, never))} (put "
                       f"them before the assert, or assert another fact)", "warning")

    def conds(self, conds: tuple, bound: set[Var], where: str, binds: bool) -> set[Var]:
        """Check conditions; return ``bound`` plus what their positive literals bind (when
        ``binds``: conditions of :when and of alternatives bind for the steps inside; :while,
        :until, :unless and wait conditions are tests)."""
        inner = set(bound)
        for c in conds:
            if isinstance(c, Literal):
                self.c.use(c, f"{where} in the body of skill {self.skill.name}")
                if not c.negated:
                    inner |= c.variables()
        for c in conds:
            if isinstance(c, Test):
                self.c.unbound(c.variables() - inner, c.loc, f"test {c} ({where})", self.HINT,
                               inner)
        return inner if binds else bound

    def step(self, node: object, bound: set[Var]) -> None:
        if isinstance(node, Act):
            self.act(node, bound)
        elif isinstance(node, Atomic):
            for part in node.steps:
                self.step(part, bound)
        elif isinstance(node, Subgoal):
            self.subgoal(node, bound)
        elif isinstance(node, ModelUpdate):
            self.c.unbound(node.fact.variables() - bound, node.loc, f"fact of {node}",
                           self.HINT, bound)
        elif isinstance(node, Wait):
            self.conds(node.conds, bound, "(wait ...)", binds=False)
        elif isinstance(node, Construct):
            self.construct(node, bound)

    def act(self, node: Act, bound: set[Var]) -> None:
        a = node.action
        self.c.unbound(a.variables() - bound, node.loc, f"action {a}", self.HINT, bound)
        if self.actions and a.name not in self.actions:
            close = difflib.get_close_matches(a.name, sorted(self.actions), n=1, cutoff=0.6)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            self.c.err(node.loc, f"action {a.name} in the body of skill {self.skill.name} "
                       f"cannot exist: the actions listed in (resources ...) are "
                       f"{', '.join(sorted(self.actions))}{hint}")

    def subgoal(self, node: Subgoal, bound: set[Var]) -> None:
        lit = node.literal
        if lit.pred not in self.c.arity:
            close = difflib.get_close_matches(lit.pred, [*WORDS, *self.c.arity], n=1,
                                              cutoff=0.7)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            self.c.err(node.loc, f"{lit} in the body of skill {self.skill.name} is neither a "
                       f"construct nor a defined concept{hint}")
            return
        if not self.c.use(lit, f"subgoal in the body of skill {self.skill.name}"):
            return
        if lit.pred not in self.achievable:
            self.c.err(node.loc, f"subgoal {lit} in the body of skill {self.skill.name} cannot "
                       f"be achieved: no skill has {lit.pred} as its head (test a condition "
                       f"with (wait ...) or a do-first alternative instead)")
        self.c.unbound(lit.variables() - bound, node.loc, f"subgoal {lit}", self.HINT, bound)

    def construct(self, node: Construct, bound: set[Var]) -> None:
        m = node.mods
        what = f"({node.name} ...)"
        inner = bound
        if m.when is not None:
            inner = self.conds(m.when, inner, f":when of {what}", binds=True)
        if m.unless is not None:
            self.conds(m.unless, inner, f":unless of {what}", binds=False)
        if m.while_ is not None:
            self.conds(m.while_, inner, f":while of {what}", binds=False)
        if m.until is not None:
            self.conds(m.until, inner, f":until of {what}", binds=False)
        for part in node.steps:
            if isinstance(part, Branch):
                here = self.conds(part.conds, inner, f"alternative of {what}", binds=True)
                for key, e in ((":utility", part.utility), (":reward", part.reward)):
                    if e is not None:
                        self.c.unbound(expr_vars(e) - here, part.loc, f"{key} {e} of an "
                                       f"alternative of {what}", self.HINT, here)
                self.step(part.step, here)
            else:
                self.step(part, inner)
