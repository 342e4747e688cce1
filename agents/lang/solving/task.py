"""The means-ends problem as data (seed 000, "Problem Solving and Skill Learning"): one
program and one cycle's percepts and beliefs, asked which (sub)goals hold and in which ways a
goal can be chained off: skill chaining (a skill clause whose head matches the goal and whose
start does not hold yet) before concept chaining (the goal's concept definition, decomposed
into its subconcepts). Pure; it decides nothing (agents/lang/solving/search.py does)."""

from __future__ import annotations

from functools import lru_cache
from itertools import islice

from ..core.arith import evaluate
from ..core.conjunction import Conjunction, conjunction_holds
from ..core.errors import EvalError, GoalError, LangError
from ..core.matcher import binding_key, holds, match_fact, solve, test_holds, unify_head
from ..core.program import ConceptClause, Program, Skill
from ..core.sexpr import Atom, read
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, PerceptPattern, Test, Var, fmt
from ..execution.effects import Effects
from ..execution.loops import situation
from ..execution.paths import btuple, show
from ..reading.goals import parse_goal
from ..reading.parser import Parser, Parts
from .bindings import BindingChoice, cheapest
from .filters import WayFilters
from .ranking import Ranking
from .relaxed import Relaxed
from .state import CONCEPT, CONJUNCTION, SKILL, Alternative

MAX_BINDINGS = 64      # candidate bindings examined per clause
MAX_PER_CLAUSE = 3     # alternatives kept per clause (the best-ranked bindings)


@lru_cache(maxsize=4096)
def condition(text: str) -> Literal | Test:
    """A condition (literal, ``(not ...)`` or test) read back from its program text."""
    forms, _ = read(f"({text})", "<solver>")
    parts = Parts()
    found = Parser("<solver>", parts).conditions(forms[0] if forms else None)
    if len(found) != 1 or parts.diags:
        raise ValueError(f"solver state: cannot read the condition {text!r}")
    return found[0]


@lru_cache(maxsize=1024)
def goal_of(text: str) -> Literal | Conjunction:
    """A (sub)goal read back from its text: a literal, or the conjunction at the bottom of a
    conjunctive goal's stack."""
    if text.startswith("(and "):
        try:
            return parse_goal(text)
        except GoalError as exc:
            raise ValueError(f"solver state: cannot read the goal {text!r}: {exc}") from None
    return literal(text)


def literal(text: str) -> Literal:
    """A (sub)goal read back from its text."""
    cond = condition(text)
    if not isinstance(cond, Literal):
        raise ValueError(f"solver state: {text!r} is not a literal")
    return cond


def pushable(cond: Literal | Test) -> bool:
    """Only a positive, ground literal can become a subgoal (no skill achieves a negation or
    a test; a variable would leave the subgoal open)."""
    return isinstance(cond, Literal) and not cond.negated and not cond.variables()


def _ground(conds: list, b: dict) -> list | None:
    """``conds`` with ``b``'s values written in, read back (the solver keeps its goals and
    learns its skills as program text); None when a value does not read back as itself (a
    symbol that is empty, spaced, a number or a variable as text: only a malformed percept or
    belief holds one): such a binding is no way to chain off."""
    if not all(map(_writable, b.values())):
        return None
    try:
        return [condition(show(c, b)) for c in conds]
    except (ValueError, LangError):
        return None


@lru_cache(maxsize=4096)
def _writable(value: object) -> bool:
    """Whether ``value`` (a binding's constant) reads back from its text as itself."""
    if not isinstance(value, str):
        return True   # numbers print as they read
    forms, diags = read(value, "<solver>")
    return not diags and len(forms) == 1 and isinstance(forms[0], Atom) and \
        forms[0].value == value


class Task(WayFilters, BindingChoice, Ranking):
    """One cycle's view of the problem: ``program`` (with the skills learned so far), the
    percepts and the beliefs; ``protected``: (goal id, text, ground literals) of the goals
    that hold and come before the one solved for, which no way chained off may undo (seed 000,
    "Adding Goal Priorities"), judged by ``effects`` (agents/lang/execution/effects.py)."""

    def __init__(self, program: Program, pidx: PerceptIndex, store: FactStore,
                 protected: tuple | list = (), effects: Effects | None = None,
                 shared: dict | None = None):
        self.program = program
        self.pidx = pidx
        self.store = store
        self.protected = tuple(protected)
        self.effects = effects if effects is not None else Effects(program)
        self.refused: list[str] = []   # ways left out because they undo a protected goal,
        self.conflicts: dict[str, str] = {}   # and those goals (id -> text)
        self.memo: dict = {}           # per-cycle results (agents/lang/solving/ordering.py)
        self.shared = shared if shared is not None else {}  # the same, across cycles, by
        #                                                     situation (``situation``)
        self._holds: dict = {}
        self._alternatives: dict = {}
        self._situation = ""
        self._reach = None   # (BindingChoice.reach)
        self._kinds: frozenset[str] | None = None
        self._relaxed: Relaxed | None = None

    @property
    def situation(self) -> str:
        """The digest of this cycle's percepts and beliefs (agents/lang/execution/loops.py), for
        results kept across cycles."""
        if not self._situation:
            self._situation = situation(self.pidx, self.store)
        return self._situation

    # -- what holds ------------------------------------------------------------------------
    def holds(self, cond: str | Literal | Test | Conjunction) -> bool:
        """True if the condition holds now (variables in a literal are existential)."""
        hit = self._holds.get(cond)
        if hit is None:
            hit = self._holds[cond] = self._holds_now(cond)
        return hit

    def _holds_now(self, cond: str | Literal | Test | Conjunction) -> bool:
        if isinstance(cond, str) and cond.startswith("(and "):
            cond = goal_of(cond)
        if isinstance(cond, Conjunction):
            return conjunction_holds(cond, self.store, self.pidx)
        c = condition(cond) if isinstance(cond, str) else cond
        if isinstance(c, Test):
            return not c.variables() and test_holds(c, {})
        found = holds(c, {}, self.store)
        return not found if c.negated else found

    def subgoal(self, text: str) -> Literal | None:
        """The condition ``text`` as a subgoal, or None when it cannot become one."""
        cond = condition(text)
        return cond if pushable(cond) else None

    def skill(self, number: int) -> Skill:
        return self.program.skills[number]

    def start_of(self, number: int, bindings: tuple) -> tuple[str, ...]:
        """The :start of skill ``number`` under ``bindings`` (text, bound variables replaced)."""
        b = {Var(k): v for k, v in bindings}
        return tuple(show(c, b) for c in self.skill(number).start)

    def type_of(self, value: object) -> str | None:
        """The type of the percept whose id is ``value``, if any: the first in name order of
        the types the primitive skills' :percepts name (what the program treats as its
        objects: ``block``; in a PDDL world ``object``, not a fact that happens to hold of
        ``value`` now, such as ``(boarded p0)``), else the first in name order."""
        types = sorted(t for (t, pid) in self.pidx.by_id if pid == value)
        if not types:
            return None
        if self._kinds is None:
            self._kinds = frozenset(p.type for s in self.program.skills
                                    if s.kind == "primitive" for p in s.percepts)
        return next((t for t in types if t in self._kinds), types[0])

    def attrs_of(self, value: object, kind: str) -> tuple:
        """The attributes a learned skill's :percepts pattern for ``value`` (a percept of type
        ``kind``) carries: those of the primitive skills' patterns of that type whose
        attributes are all constants and which ``value``'s percept matches, the one fewest
        percepts match (``(object ?o1 type truck)``, not ``(object ?o1)``, which any object
        matches: a skill with three such patterns would try every triple of objects)."""
        key = ("attrs", kind)
        pats = self.memo.get(key)
        if pats is None:
            found = {p.attrs for s in self.program.skills if s.kind == "primitive"
                     for p in s.percepts if p.type == kind and p.attrs and
                     not any(isinstance(t, Var) for _, t in p.attrs)}
            pats = self.memo[key] = sorted(
                (sum(1 for _ in islice(solve([PerceptPattern(kind, Var("x"), a)], {},
                                             self.pidx, self.store), MAX_BINDINGS)), a)
                for a in found)
        for _, attrs in pats:
            if next(solve([PerceptPattern(kind, value, attrs)], {}, self.pidx, self.store),
                    None) is not None:
                return attrs
        return ()

    # -- ways to chain off a goal ----------------------------------------------------------
    def nothing_to_chain(self, goal: str) -> str:
        """Why ``goal`` has no way to chain off, for the failure's reason."""
        refused = f"; {'; '.join(dict.fromkeys(self.refused))}" if self.refused else ""
        if goal.startswith("(and "):
            return ("nothing to chain off: its conjuncts cannot be bound to objects here, or "
                    "one that does not hold cannot become a subgoal (a negation or a test)"
                    + refused)
        pred = literal(goal).pred
        skills = f"no primitive skill achieves {pred}" if not any(
            s.kind == "primitive" for s in self.program.skills_for(pred)) else \
            f"no primitive skill for {pred} applies here (its :percepts do not match, or its " \
            "start could not become subgoals)"
        concept = "its definition cannot be decomposed here" \
            if any(c.relations for c in self.program.concepts.get(pred, ())) else \
            f"{pred} is a primitive concept, with no subconcepts to decompose into"
        return f"nothing to chain off: {skills}; {concept}{refused}"

    def alternatives(self, goal: Literal | Conjunction, applicable: bool = False,
                     concepts: bool = True) -> tuple[Alternative, ...]:
        """Skill chaining first, then concept chaining (seed 000: "chaining backwards off
        either conceptual clauses or primitive skills, with a priority on the latter"): the
        primitive skills for the goal in program order, then its concept clauses; within a
        clause the best-ranked bindings (``rank``), at most MAX_PER_CLAUSE of them. Skills
        with subgoals (learned or written) are not chained off: the executive already found
        none of them executable, and their starts are compound.
        ``applicable``: also the skills whose conditions all hold already (a planner that
        projects operators ahead of execution applies them; the solver never needs them, the
        executive would have executed such a skill); ``concepts``: concept chaining too
        (PRODIGY's back-chainer, agents/lang/planning, chains on operators only).
        A conjunction has one way per binding of its variables, like a concept clause without
        a head (concept chaining on its conjuncts)."""
        key = (goal, applicable, concepts)
        hit = self._alternatives.get(key)
        if hit is not None:
            return hit
        if isinstance(goal, Conjunction):
            out = self._by_conjunction(goal)
        else:
            out = [a for s in self.program.skills_for(goal.pred) if s.kind == "primitive"
                   for a in self._by_skill(s, goal, applicable)]
            for clause in self.program.concepts.get(goal.pred, ()) if concepts else ():
                out += self._by_concept(clause, goal)
        self._alternatives[key] = hit = tuple(out)
        return hit

    def _by_skill(self, s: Skill, goal: Literal, applicable: bool = False
                  ) -> list[Alternative]:
        b0 = unify_head(s.head, goal, {})
        if b0 is None:
            return []
        conds = [*s.start, *s.requires]
        ranked = []
        for b in self._candidates(list(s.percepts), conds, b0):
            ground = _ground(conds, b)
            if ground is not None and self._chainable(ground, applicable) \
                    and self.admits(s, b, goal) and not self.undoes_skill(s, b) and \
                    (applicable or not self._circular(goal, ground)):
                ready = applicable and all(self.holds(c) for c in ground)
                ranked.append(((not ready,), binding_key(b), b, ground))
        return [Alternative(SKILL, s.number, s.name, btuple(b), tuple(map(str, ground)),
                            self._shows(s, b))
                for _, _, b, ground in self._best(self._ranks(ranked), not applicable)]

    def admits(self, s: Skill, b: dict, goal: Literal) -> bool:
        """Whether skill ``s`` under bindings ``b`` may be chained on for ``goal`` at all
        (before the best-ranked are kept); the planner's failure memory says no to a choice
        that failed (agents/lang/planning/backchain.py)."""
        return True

    def _by_concept(self, clause: ConceptClause, goal: Literal) -> list[Alternative]:
        b0 = unify_head(clause.head, goal, {})
        if b0 is None or not clause.relations:
            return []
        ranked: list = []
        for anything in (False, True):   # any object only when the beliefs give no way
            for b in self._candidates(list(clause.percepts), list(clause.relations), b0,
                                      anything):
                if next(solve([*clause.percepts, *clause.tests], b, self.pidx, self.store),
                        None) is None:
                    continue
                ground = _ground(clause.relations, b)
                if ground is not None and self._chainable(ground) and \
                        self._possible(ground, f"concept {clause.head.pred}#{clause.index} "
                                               f"{show(clause.head, b)}"):
                    ranked.append(((), binding_key(b), b, ground))
            if ranked:
                break
        ranked = self._ranks(ranked)
        name = f"{clause.head.pred}#{clause.index}"
        open_ = len(ranked) > 1 and any(set(r[2]) - set(b0) for r in ranked)
        return [Alternative(CONCEPT, clause.index, name, btuple(b), tuple(map(str, ground)),
                            f"concept {name}")
                for _, _, b, ground in (cheapest(self, ranked) if open_ else
                                        self._best(ranked))]

    def _by_conjunction(self, conj: Conjunction) -> list[Alternative]:
        ranked: list = []
        for anything in (False, True):   # any object only when the beliefs give no way
            for b in self._candidates([], list(conj.literals), {}, anything):
                ground = _ground(list(conj.conds), b)
                if ground is not None and self._chainable(ground) and \
                        not self.impossible(ground):   # (most bindings are: not noted)
                    ranked.append(((), binding_key(b), b, ground))
            if ranked:
                break
        ranked = self._ranks(ranked)
        return [Alternative(CONJUNCTION, 0, "and", btuple(b), tuple(map(str, ground)),
                            "the conjunction")
                for _, _, b, ground in (cheapest(self, ranked) if len(ranked) > 1 else
                                        ranked)]

    def _chainable(self, ground: list, applicable: bool = False) -> bool:
        """Something is left to achieve (or, ``applicable``, nothing), and all of it can
        become a subgoal."""
        unsat = [c for c in ground if not self.holds(c)]
        return (applicable or bool(unsat)) and all(pushable(c) for c in unsat)

    per_clause = MAX_PER_CLAUSE   # bindings kept per clause (the planner keeps more)

    def _best(self, ranked: list, closest: bool = True) -> list:
        """The best-ranked bindings of a clause, at most ``per_clause``; with ``closest``
        (the solver's chaining), none that holds fewer of the conditions than the best one
        (a block not on B3 is no way to clear B3: it would first have to be put there). The
        planner, which projects its operators, keeps them all. The relaxed estimate comes
        first where there is one (agents/lang/solving/relaxed.py): a binding whose conditions
        are fewer rounds away goes first, one that can never hold last."""
        ranked.sort(key=lambda r: (r[0], r[1]))
        best = ranked[:self.per_clause]
        return [r for r in best if r[0][:-1] == best[0][0][:-1]] if closest else best

    def _candidates(self, percepts: list, conds: list, b0: dict, anything: bool = False
                    ) -> list[dict]:
        """Bindings of the clause's variables: its :percepts matched, then any variable left
        taken from beliefs matching a positive condition (in written order), and, with
        ``anything`` (a concept's or a conjunction's relations, when the beliefs give no
        way), also each variable from the objects perceived (``(on ?x A)`` with nothing on
        A: each block may be put there; ``Task.impossible`` then leaves out what nothing can
        make true). A variable the goal does not fix names an object of its own: one the goal
        or another such variable names is not taken (no (unstack B B) to clear B)."""
        sols = list(islice(solve(percepts, b0, self.pidx, self.store), MAX_BINDINGS)) \
            if percepts else [b0]
        lits = [c for c in conds if isinstance(c, Literal) and not c.negated]
        out: dict = {}
        fixed = set(b0.values())
        for b in sols:
            for nb in self._bind_rest(lits, b, anything):
                extra = [v for k, v in nb.items() if k not in b0]
                if len(set(extra)) == len(extra) and not fixed & set(extra):
                    out.setdefault(binding_key(nb), nb)
        return [out[k] for k in sorted(out)][:MAX_BINDINGS]

    def _bind_rest(self, lits: list[Literal], b: dict, anything: bool = False) -> list[dict]:
        for i, lit in enumerate(lits):
            if all(v in b for v in lit.variables()):
                continue
            matches = list(islice(match_fact(lit, b, self.store), MAX_BINDINGS))
            if matches:
                found = [x for m in matches
                         for x in self._bind_rest(lits[i + 1:], m, anything)]
                return found + self._any(lits, b) if anything else found
        return self._any(lits, b) if anything else [b]

    @staticmethod
    def _shows(s: Skill, b: dict) -> str:
        if s.kind != "primitive":
            return f"{s.name} {show(s.head, b)}"
        try:
            return " ".join("(" + " ".join([a.name.lstrip("*"),
                                            *(fmt(evaluate(x, b)) for x in a.args)]) + ")"
                            for a in s.actions)
        except EvalError:
            return f"{s.name} {show(s.head, b)}"
