"""Semantic checks that turn parsed parts into a Program, reporting every problem at once:
undefined concepts, arity mismatches, unbound variables, unstratified negation (seed 000); a
mechanism's facts, sections and skill bodies are checked through its hooks
(agents/lang/core/mechanism.py)."""

from __future__ import annotations

import difflib
from collections.abc import Collection
from dataclasses import replace

from ..core.conjunction import goal_literals
from ..core.errors import Diagnostic, ProgramError
from ..core.mechanism import body_reader
from ..core.program import ConceptClause, Program, Skill
from ..core.terms import Literal, Loc, Test, Var
from .goals import enumerable
from .parser import Parts
from .stratify import dependency_graph, negative_cycle, sccs

MAX_SUGGESTIONS = 20
"""'did you mean' is searched for the first MAX_SUGGESTIONS unknown names only, among at most
MAX_SUGGESTION_NAMES known names: each search compares with every known name, so a large
program full of unknown names stays fast."""
MAX_SUGGESTION_NAMES = 2000


class Checker:
    """Collects diagnostics for one program."""

    def __init__(self, parts: Parts):
        self.parts = parts
        self.diags = parts.diags
        self.arity: dict[str, int] = {}
        self.arity_loc: dict[str, Loc | None] = {}
        self.suggestions = 0

    def close_match(self, name: str, known: Collection[str], cutoff: float) -> str | None:
        """The known name closest to `name` (difflib), while MAX_SUGGESTIONS are not used up."""
        self.suggestions += 1
        if self.suggestions > MAX_SUGGESTIONS or len(known) > MAX_SUGGESTION_NAMES:
            return None
        close = difflib.get_close_matches(name, list(known), n=1, cutoff=cutoff)
        return close[0] if close else None

    def err(self, loc: Loc | None, msg: str, severity: str = "error") -> None:
        src, line, col = (loc.source, loc.line, loc.col) if loc else ("<program>", 0, 0)
        self.diags.append(Diagnostic(src, line, col, msg, severity))

    def run(self) -> Program:
        concepts: dict[str, list[ConceptClause]] = {}
        for c in self.parts.concepts:
            group = concepts.setdefault(c.head.pred, [])
            group.append(replace(c, index=len(group) + 1))
            self.define(c.head)
        mechanisms = self.parts.mechanisms
        model = [u for m in mechanisms for u in m.asserted(self.parts.skills)]
        for u in model:   # the world model's predicates (seed 002: assert, retract)
            if u.fact.pred not in self.arity:
                self.define(u.fact)
        for u in model:
            self.use(u.fact, f"fact of {u}")
        for clauses in concepts.values():
            for c in clauses:
                self.check_concept(c)
        sections = [x for items in self.parts.sections.values() for x in items]
        for item in sections:   # a mechanism's own predicates (the planner's, seed 003)
            item.define(self)
        reader = body_reader(mechanisms)
        self.bodies = None if reader is None else \
            reader.body_checks(self, self.parts.skills, self.parts.resources)
        skills = []
        by_pred: dict[str, list[Skill]] = {}
        for n, s in enumerate(self.parts.skills):
            group = by_pred.setdefault(s.head.pred, [])
            s = replace(s, index=len(group) + 1, number=n)
            group.append(s)
            skills.append(s)
            self.check_skill(s)
        for g in self.parts.goals:
            for lit in goal_literals(g.literal):
                self.use(lit, "goal" if lit is g.literal else f"conjunct of goal {g.literal}")
        self.check_goal_variables(concepts)
        self.check_resources(skills)
        for item in sections:
            item.check(self)
        strata = self.stratify(concepts)
        errors = [d for d in self.diags if d.severity == "error"]
        if errors:
            raise ProgramError(sorted(self.diags, key=_order))
        return Program(
            concepts={k: tuple(v) for k, v in concepts.items()}, arity=dict(self.arity),
            skills=tuple(skills), goals=tuple(self.parts.goals), resources=self.parts.resources,
            strata=strata, warnings=tuple(sorted(self.diags, key=_order)),
            sources=tuple(self.parts.sources),
            skills_by_pred={k: tuple(v) for k, v in by_pred.items()},
            sections={k: tuple(v) for k, v in self.parts.sections.items()},
            mechanisms=mechanisms)

    # -- names and arities -------------------------------------------------------------------
    def define(self, head: Literal) -> None:
        n = len(head.args)
        if head.pred in self.arity and self.arity[head.pred] != n:
            self.err(head.loc, f"concept {head.pred} defined with {n} argument(s) here but with "
                     f"{self.arity[head.pred]} at {self.arity_loc[head.pred]}")
            return
        self.arity.setdefault(head.pred, n)
        self.arity_loc.setdefault(head.pred, head.loc)

    def use(self, lit: Literal, what: str) -> bool:
        if lit.pred not in self.arity:
            close = self.close_match(lit.pred, self.arity, 0.7)
            hint = f" (did you mean '{close}'?)" if close else ""
            self.err(lit.loc, f"undefined concept '{lit.pred}' in {lit} ({what}){hint}")
            return False
        want = self.arity[lit.pred]
        if len(lit.args) != want:
            self.err(lit.loc, f"{lit} ({what}): concept {lit.pred} takes {want} argument(s), "
                     f"got {len(lit.args)} (defined at {self.arity_loc[lit.pred]})")
            return False
        return True

    # -- clauses -----------------------------------------------------------------------------
    def check_concept(self, c: ConceptClause) -> None:
        bound: set[Var] = set()
        for p in c.percepts:
            bound |= p.variables()
        for lit in c.relations:
            self.use(lit, f":relations of concept {c.head.pred}#{c.index}")
            if not lit.negated:
                bound |= lit.variables()
        for t in c.tests:
            self.unbound(t.variables() - bound, t.loc, f"test {t} of concept {c.head}",
                         "bind it in :percepts or a positive :relations entry", bound)
        self.unbound(c.head.variables() - bound, c.head.loc, f"head {c.head}",
                     "bind it in :percepts or a positive :relations entry", bound)

    def check_skill(self, s: Skill) -> None:
        self.use(s.head, f"head of skill {s.name}")
        bound = set(s.head.variables())
        for p in s.percepts:
            bound |= p.variables()
        for part, conds in ((":start", s.start), (":requires", s.requires)):
            for cond in conds:
                if isinstance(cond, Literal):
                    self.use(cond, f"{part} of skill {s.name}")
                    if not cond.negated:
                        bound |= cond.variables()
        for part, conds in ((":start", s.start), (":requires", s.requires)):
            for cond in conds:
                if isinstance(cond, Test):
                    self.unbound(cond.variables() - bound, cond.loc, f"test {cond} in {part}",
                                 "bind it in the head, :percepts or a positive condition",
                                 bound)
        for g in s.subgoals:
            self.use(g, f":subgoals of skill {s.name}")
            self.unbound(g.variables() - bound, g.loc, f"subgoal {g}",
                         "bind it in the head, :percepts, :start or :requires", bound)
        for e in s.effects:
            self.use(e, f":effects of skill {s.name}")
        for a in s.actions:
            self.unbound(a.variables() - bound, a.loc, f"action {a}",
                         "bind it in the head, :percepts, :start or :requires", bound)
        if s.body is not None and self.bodies is not None:
            self.bodies.check(s, bound)

    def unbound(self, vs: set[Var], loc: Loc | None, where: str, hint: str,
                bound: set[Var] = frozenset()) -> None:
        names = sorted(v.name for v in bound)
        for v in sorted(vs, key=lambda v: v.name):
            close = self.close_match(v.name, names, 0.6)
            typo = f" (did you mean ?{close}?)" if close else ""
            self.err(loc, f"variable ?{v.name} in {where} is bound nowhere{typo}; {hint}")

    def check_goal_variables(self, concepts: dict[str, list[ConceptClause]]) -> None:
        """A goal variable must mean "every instance", so its concept must take it from
        percepts in every clause (agents/lang/reading/goals.py, ``enumerable``)."""
        view = Program({k: tuple(v) for k, v in concepts.items()}, {}, (), ())
        for g in self.parts.goals:
            if isinstance(g.literal, Literal) and g.literal.pred in concepts:
                why = enumerable(g.literal, view)
                if why:
                    self.err(g.literal.loc, f"goal {g.literal}: {why}")

    def check_resources(self, skills: list[Skill]) -> None:
        table = self.parts.resources
        if table is None:
            return
        seen: set[str] = set()
        for s in skills:
            for a in s.actions:
                if a.name not in table and a.name not in seen:
                    seen.add(a.name)
                    self.err(a.loc, f"action {a.name} is not listed in (resources ...); it is "
                             "treated as using every resource", "warning")

    def stratify(self, concepts: dict[str, list[ConceptClause]]):
        graph = dependency_graph(c for cl in concepts.values() for c in cl)
        out = []
        for comp in sccs(graph):
            comp = [p for p in comp if p in concepts]
            if not comp:
                continue
            found = negative_cycle(graph, comp)
            if found is not None:
                lit, cycle = found
                self.err(lit.loc, "negation is not stratified: " + " -> ".join(cycle)
                         + f" (the cycle passes through {lit}); a concept may not depend on "
                         "the negation of itself")
            recursive = len(comp) > 1 or comp[0] in graph.get(comp[0], {})
            out.append((tuple(comp), recursive))
        return tuple(out)


def _order(d: Diagnostic) -> tuple:
    return (d.source, d.line, d.col, d.message)


def build_program(parts: Parts) -> Program:
    """Check ``parts``; return the Program or raise ProgramError with every diagnostic."""
    return Checker(parts).run()
