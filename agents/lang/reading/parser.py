"""From s-expressions to program parts, collecting every diagnostic (file:line:col).

A file holds sections ``(concepts ...)``, ``(skills ...)``, ``(goals ...)``, ``(resources ...)``, or
bare clauses ``((head ...) :key value ...)`` as printed in seed 000's tables (a clause with :start,
:requires, :subgoals, :actions or :body is a skill, otherwise a concept). A mechanism's own
sections (the planner's, seed 003) and the reader of a skill's ``:body`` (SCS, seed 002) come
with the mechanisms the parts are read with (Mechanism.sections, Mechanism.read_body).
"""

from __future__ import annotations

from ..core.arith import OPS
from ..core.conjunction import Goal, is_conjunction, read_conjunction
from ..core.errors import Diagnostic
from ..core.limits import MAX_DIAGNOSTICS
from ..core.mechanism import body_reader
from ..core.program import ConceptClause, GoalSpec, Skill
from ..core.sexpr import Atom, SList, to_text
from ..core.terms import Literal, Loc, Test
from .pieces import PieceParser, op_name, suggest

CONCEPT_KEYS = (":percepts", ":relations", ":tests")
SKILL_KEYS = (":percepts", ":start", ":requires", ":subgoals", ":actions", ":tests", ":body",
              ":effects")
KEY_ALIASES = {":require": ":requires"}  # seed 000, Table 6 misspelling: accepted with a warning
SKILL_MARKERS = {":start", ":requires", ":require", ":subgoals", ":actions", ":body"}


class Parts:
    """Everything read from one or more files, before semantic checks; ``mechanisms``: those
    that read their sections and skill bodies (agents/lang/core/mechanism.py)."""

    def __init__(self, mechanisms: tuple = ()) -> None:
        self.mechanisms = tuple(mechanisms)
        self.concepts: list[ConceptClause] = []
        self.skills: list[Skill] = []
        self.goals: list[GoalSpec] = []
        self.resources: dict[str, frozenset[str]] | None = None
        self.resource_locs: dict[str, Loc] = {}
        self.diags: list[Diagnostic] = []
        self.sources: list[str] = []
        # a mechanism's own sections (SECTIONS): name -> items, each with define(checker)
        # and check(checker), called by agents/lang/reading/checks.py
        self.sections: dict[str, list] = {}


class Parser(PieceParser):
    """Reads top-level forms of one source into ``Parts``."""

    def __init__(self, source: str, parts: Parts):
        self.source = source
        self.parts = parts
        self.sections = sections_of(parts.mechanisms)
        self.body_reader = body_reader(parts.mechanisms)

    # -- helpers ---------------------------------------------------------------------------
    def loc(self, node: Atom | SList) -> Loc:
        return Loc(self.source, node.line, node.col)

    def err(self, node: Atom | SList, msg: str, severity: str = "error") -> None:
        self.parts.diags.append(Diagnostic(self.source, node.line, node.col, msg, severity))

    # -- top level -------------------------------------------------------------------------
    def form(self, node: Atom | SList) -> None:
        if isinstance(node, Atom):
            self.err(node, f"expected a section or a clause in parentheses, got {to_text(node)}")
            return
        if not node.items:
            self.err(node, "empty list () at top level")
            return
        first = node.items[0]
        if isinstance(first, SList):
            self.clause(node)
            return
        name = first.value
        handler = self.sections.get(name) if isinstance(name, str) else None
        if handler is None:
            self.err(first, f"unknown section '{to_text(first)}'{suggest(name, self.sections)} "
                     f"(expected one of: {', '.join(self.sections)}, or clauses ((head ...) "
                     ":key ...))")
            return
        handler(self, node)

    def section_clauses(self, node: SList, want: str) -> None:
        for item in node.items[1:]:
            if isinstance(item, SList) and item.items and isinstance(item.items[0], SList):
                self.clause(item, want)
            else:
                self.err(item, f"expected a clause ((head ...) :key value ...) in ({want} ...), "
                         f"got {to_text(item)}")

    def goals_section(self, node: SList) -> None:
        for item in node.items[1:]:
            goal = self.goal(item)
            if goal is not None:
                self.parts.goals.append(GoalSpec(goal, self.loc(item)))

    def goal(self, node: object) -> Goal | None:
        """A goal: one literal, or ``(and ...)`` of conditions (agents/lang/core/conjunction.py)."""
        if is_conjunction(node):
            return read_conjunction(self, node)
        return self.literal(node, "goal", allow_not=False)

    def resources_section(self, node: SList) -> None:
        table = self.parts.resources if self.parts.resources is not None else {}
        for item in node.items[1:]:
            if not (isinstance(item, SList) and item.items and isinstance(item.items[0], Atom)):
                self.err(item, f"expected (*action resource ...) in (resources ...), "
                         f"got {to_text(item)}")
                continue
            name = item.items[0].value
            if not (isinstance(name, str) and name.startswith("*")):
                self.err(item.items[0], f"resource entry must start with an action name such as "
                         f"*gas, got {to_text(item.items[0])}")
                continue
            res = []
            for r in item.items[1:]:
                if isinstance(r, Atom) and isinstance(r.value, str):
                    res.append(r.value)
                else:
                    self.err(r, f"resource names are symbols, got {to_text(r)}")
            if name in table:
                self.err(item, f"resources of {name} given twice (first at "
                         f"{self.parts.resource_locs[name]})")
            table[name] = frozenset(res)
            self.parts.resource_locs[name] = self.loc(item)
        self.parts.resources = table

    # -- clauses ---------------------------------------------------------------------------
    def clause(self, node: SList, want: str | None = None) -> None:
        head = self.literal(node.items[0], "clause head", allow_not=False)
        fields: dict[str, SList] = {}
        items = node.items[1:]
        for i in range(0, len(items), 2):
            key = items[i]
            if not (isinstance(key, Atom) and isinstance(key.value, str)
                    and key.value.startswith(":")):
                self.err(key, f"expected a keyword such as :percepts, got {to_text(key)}")
                continue
            name = key.value
            if name in KEY_ALIASES:
                self.err(key, f"'{name}' read as '{KEY_ALIASES[name]}' (misspelling)", "warning")
                name = KEY_ALIASES[name]
            if i + 1 >= len(items) or not isinstance(items[i + 1], SList):
                self.err(key, f"{name} needs a list after it")
                continue
            if name in fields:
                self.err(key, f"{name} given twice in the same clause")
            fields[name] = items[i + 1]
        kind = want or ("skills" if SKILL_MARKERS & set(fields) else "concepts")
        allowed = SKILL_KEYS if kind == "skills" else CONCEPT_KEYS
        for name in fields:
            if name not in allowed:
                self.err(fields[name], f"keyword {name} is not allowed in a "
                         f"{kind[:-1]}{suggest(name, allowed)} (allowed: {' '.join(allowed)})")
        if head is None:
            return
        if kind == "skills":
            self.skill(node, head, fields)
        else:
            self.concept(node, head, fields)

    def concept(self, node: SList, head: Literal, f: dict[str, SList]) -> None:
        if not (f.get(":percepts") or f.get(":relations") or f.get(":tests")):
            self.err(node, f"concept {head} has no body: give :percepts and/or :relations")
        self.parts.concepts.append(ConceptClause(
            head, self.patterns(f.get(":percepts")), tuple(self.conditions(f.get(":relations"),
                                                                           tests=False)),
            self.tests(f.get(":tests")), self.loc(node)))

    def skill(self, node: SList, head: Literal, f: dict[str, SList]) -> None:
        has = [k for k in (":subgoals", ":actions", ":body") if k in f]
        if len(has) > 1:
            self.err(node, f"skill {head} gives {' and '.join(has)}; give exactly one")
        elif not has:
            self.err(node, f"skill {head} needs :actions (primitive), :subgoals (nonprimitive) "
                     "or :body (SCS constructs, seed 002)")
        start = self.conditions(f.get(":start")) + [Test(t.expr, t.loc)
                                                    for t in self.tests(f.get(":tests"))]
        subgoals = tuple(x for x in (self.literal(s, "subgoal", allow_not=False)
                                     for s in self.items(f.get(":subgoals"), "subgoals (goal ?x)"))
                         if x is not None)
        actions = tuple(x for x in (self.action(a) for a in self.items(
            f.get(":actions"), "actions (*name arg ...)")) if x is not None)
        before = len(self.parts.diags)
        body = self.read_body(f[":body"]) if ":body" in f else None
        if ":body" in f and body is None and len(self.parts.diags) == before:
            self.err(f[":body"], f"skill {head}: :body could not be read")
        effects = tuple(x for x in (self.literal(e, "effect") for e in self.items(
            f.get(":effects"), "effects (concept ?x) or (not (concept ?x))")) if x is not None)
        if effects and ":actions" not in f:
            self.err(f[":effects"], f"skill {head}: :effects are those of a primitive skill's "
                     ":actions; give :actions")
        self.parts.skills.append(Skill(
            head, self.patterns(f.get(":percepts")), tuple(start),
            tuple(self.conditions(f.get(":requires"))), subgoals, actions, body, self.loc(node),
            effects=effects))

    def read_body(self, node: SList) -> object:
        """The step tree of a ``:body``, read by the mechanism that reads bodies."""
        if self.body_reader is None:
            self.err(node, ":body is read by no mechanism of this engine")
            return None
        return self.body_reader.read_body(self, node)

    # -- pieces ----------------------------------------------------------------------------
    def literal(self, node: object, what: str, allow_not: bool = True) -> Literal | None:
        if not (isinstance(node, SList) and node.items):
            self.err(node, f"expected a {what} such as (at-street ?self ?street), got "
                     f"{to_text(node)}")
            return None
        first = node.items[0]
        if isinstance(first, Atom) and first.value == "not" and allow_not:
            if len(node.items) != 2:
                self.err(node, f"(not ...) takes exactly one {what}, got {len(node.items) - 1}")
                return None
            inner = self.literal(node.items[1], what, allow_not=False)
            return None if inner is None else Literal(inner.pred, inner.args, True, inner.loc)
        if not (isinstance(first, Atom) and isinstance(first.value, str)):
            self.err(node, f"a {what} must start with a concept name, got {to_text(first)}")
            return None
        args = []
        for a in node.items[1:]:
            if isinstance(a, Atom):
                args.append(a.value)
            else:
                self.err(a, f"arguments of {what} {first.value} are constants or variables, "
                         f"got {to_text(a)}")
                return None
        return Literal(first.value, tuple(args), False, self.loc(node))

    def conditions(self, node: SList | None, tests: bool = True) -> list:
        """Literals (possibly negated) and, where ``tests``, inline tests such as (< ?x 3)."""
        out: list = []
        for item in self.items(node, "conditions (concept ?x) or (not (concept ?x))"):
            op = op_name(item)
            inner = item.items[1] if op == "not" and len(item.items) == 2 else None
            if not tests and (op in OPS or op_name(inner) in OPS):
                self.err(item, f"{to_text(item)} is a test; write it under :tests, not "
                         ":relations")
                continue
            if tests and (op in OPS or op_name(inner) in OPS):
                t = self.test(item)
                if t is not None:
                    out.append(t)
                continue
            lit = self.literal(item, "condition")
            if lit is not None:
                out.append(lit)
        return out


SECTIONS = {
    "concepts": lambda p, n: p.section_clauses(n, "concepts"),
    "skills": lambda p, n: p.section_clauses(n, "skills"),
    "goals": Parser.goals_section,
    "resources": Parser.resources_section,
}
"""The kernel's sections; a mechanism's follow (Mechanism.sections: (operators ...),
(requests ...), (control-rules ...) of the planner, seed 003)."""


def sections_of(mechanisms: tuple) -> dict:
    """Section name -> handler(parser, node): the kernel's, then each mechanism's."""
    out = dict(SECTIONS)
    for m in mechanisms:
        out.update(m.sections())
    return out


def parse_forms(forms: list, source: str, parts: Parts) -> None:
    """Add every top-level form of ``source`` to ``parts``; stop after MAX_DIAGNOSTICS
    problems of this source (limits.py), saying where."""
    p = Parser(source, parts)
    before = len(parts.diags)
    for f in forms:
        if len(parts.diags) - before > MAX_DIAGNOSTICS:
            p.err(f, f"more than {MAX_DIAGNOSTICS} problems; the rest of {source} is not "
                  "checked")
            return
        p.form(f)

