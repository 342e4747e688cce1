"""The means-ends problem as data (seed 000, "Problem Solving and Skill Learning"): one
program and one cycle's percepts and beliefs, asked which (sub)goals hold and in which ways a
goal can be chained off: skill chaining (a skill clause whose head matches the goal and whose
start does not hold yet) before concept chaining (the goal's concept definition, decomposed
into its subconcepts; agents/lang/solving/ways.py). Pure; it decides nothing
(agents/lang/solving/search.py does). The goals and conditions as text: text.py."""


from __future__ import annotations

from itertools import islice

from ..core.conjunction import Conjunction, conjunction_holds
from ..core.matcher import holds, solve, test_holds, unify_head
from ..core.program import Program, Skill
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, PerceptPattern, Test, Var
from ..execution.effects import Effects
from ..execution.loops import situation
from ..execution.paths import show
from .bindings import BindingChoice
from .relaxed import Relaxed
from .state import condition, goal_of, pushable
from .ways import MAX_BINDINGS, WayFilters, Ways

# -- ranking the bindings of a way to chain off: the most conditions holding, after the
# relaxed estimate (relaxed.py) where the program admits one; a single binding is not ranked

_INF = float("inf")


class Ranking:
    """Needs the Task's program, holds, shared, situation and ``_relaxed``."""

    def _ranks(self, rows: list) -> list:
        """``rows`` (prefix, key, binding, ground conditions) with each prefix extended by
        the rank of its conditions (``rank``); a single row is left as it is: there is nothing
        to order it against, and the relaxed estimate is the costliest part of a cycle."""
        if len(rows) <= 1:
            return rows
        return [((*p, *self.rank(g)), k, b, g) for p, k, b, g in rows]

    def rank(self, conds: list) -> tuple:
        """Sort key of a way to chain off (smaller first): the most conditions holding,
        counting for a false literal the subconcepts of its definition that hold; ties go to
        the one whose earlier conditions hold (seed 000, Figure 3: (unstack B A), since
        (on B A) holds, before (unstack C A))."""
        bits: list[int] = []
        for c in conds:
            ok = self.holds(c)
            bits.append(int(ok))
            if not ok and isinstance(c, Literal) and not c.negated:
                bits += self._sub_bits(c)
        base = (-sum(bits), tuple(-x for x in bits))
        h = self.estimate(conds)
        return base if h is None else (h, *base)

    def estimated(self) -> bool:
        """Whether the program admits the relaxed estimate (agents/lang/solving/relaxed.py)."""
        if self._relaxed is None:
            self._relaxed = self._situation_relaxed()
        return self._relaxed.available

    def estimate(self, conds: list) -> float | None:
        """The relaxed distance of ``conds`` (agents/lang/solving/relaxed.py): the sum of the
        levels of the positive ground literals that do not hold, infinite when one never
        can; None where the program admits no such estimate."""
        if self._relaxed is None:
            self._relaxed = self._situation_relaxed()
        if not self._relaxed.available:
            return None
        total = 0
        for c in conds:
            if isinstance(c, Literal) and not c.negated and not c.variables() and \
                    not self.holds(c):
                k = self._relaxed.level(c)
                if k is None:
                    return _INF
                total += k
        return total

    def _situation_relaxed(self) -> Relaxed:
        """The relaxed levels of this situation: kept across cycles in ``shared`` (a cycle
        spent deciding leaves the situation as it was), with the program they were for."""
        key = ("relaxed", self.situation)
        hit = self.shared.get(key)
        if hit is None or hit.task.program is not self.program:
            hit = self.shared[key] = Relaxed(self)
        return hit

    def _sub_bits(self, lit: Literal) -> list[int]:
        best: list[int] = []
        for clause in self.program.concepts.get(lit.pred, ()):
            b = unify_head(clause.head, lit, {})
            if b is None or not clause.relations:
                continue
            bits = [int(self.holds(show(r, b))) for r in clause.relations]
            if (sum(bits), bits) > (sum(best), best):
                best = bits
        return best


class Task(Ways, WayFilters, BindingChoice, Ranking):
    """One cycle's view of the problem: ``program`` (with the skills learned so far), the
    percepts and the beliefs; ``protected``: (goal id, text, ground literals) of the goals
    that hold and come before the one solved for, which no way chained off may undo (seed 000,
    "Adding Goal Priorities"), judged by ``effects`` (agents/lang/execution/effects.py);
    ``undone``: what the last cycle's actions undid."""

    def __init__(self, program: Program, pidx: PerceptIndex, store: FactStore,
                 protected: tuple | list = (), effects: Effects | None = None,
                 shared: dict | None = None, undone: tuple[Literal, ...] = ()):
        self.program = program
        self.undone = undone   # what the last cycle's actions undid (ground patterns): the
        #                        agenda puts none of it straight back (ordering.py)
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
