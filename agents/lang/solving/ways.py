"""The ways to chain off a goal (seed 000, "Problem Solving and Skill Learning"): skill
chaining (a primitive skill whose head matches the goal and whose start does not hold yet)
before concept chaining (the goal's concept definition, decomposed into its subconcepts), and
a conjunction's bindings; within a clause the best-ranked bindings; and the ways left out
(``WayFilters``): a skill whose actions would undo a protected goal, a higher one
that holds (seed 000, "Adding Goal Priorities"), and a way whose own condition can only be
reached through the goal it is for (a landmark of the condition; landmarks.py). Mixins of Task
(agents/lang/solving/task.py), which holds the cycle's percepts and beliefs."""

from __future__ import annotations

from itertools import islice

from ..core.arith import evaluate
from ..core.conjunction import Conjunction
from ..core.errors import EvalError
from ..core.matcher import binding_key, match_fact, solve, unify_head
from ..core.matcher import ground as ground_literal
from ..core.program import ConceptClause, Skill
from ..core.terms import Action, Literal, fmt
from ..execution.effects import undone_goal
from ..execution.paths import btuple, show
from .bindings import cheapest
from .landmarks import key, landmarks
from .state import (
    CONCEPT,
    CONJUNCTION,
    SKILL,
    Alternative,
    condition,
    grounded,
    literal,
    pushable,
)

MAX_BINDINGS = 64      # candidate bindings examined per clause
MAX_PER_CLAUSE = 3     # alternatives kept per clause (the best-ranked bindings)


class Ways:
    """Task's ways to chain off a goal (needs Task's ``program``, ``pidx``, ``store``,
    ``holds`` and the filters and rankings of WayFilters, BindingChoice and Ranking)."""

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
        clause the best-ranked bindings (``rank``), at most MAX_PER_CLAUSE of them. Where the
        program admits the relaxed estimate, the primitive skills' ways are ordered by it
        (stable: program order among equals): a package is unloaded at an airport from the
        airplane that can bring it, not from a truck that could only be loaded there. Skills
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
            if len(out) > 1 and not applicable and self.estimated():
                out.sort(key=lambda a: self.estimate([condition(c) for c in a.conditions]))
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
        ranked: list = []
        fixed = set(b0.values())
        # objects shared only when no binding keeps them apart, or where the relaxed
        # estimate judges every binding (it ranks (unstack B B) never; elevators' passenger
        # count n1 may well be the floor n1): then, all else equal, objects kept apart first
        for shared in (True,) if self.estimated() else (False, True):
            for b in self._candidates(list(s.percepts), conds, b0, shared=shared):
                ground = grounded(conds, b)
                if ground is not None and self._chainable(ground, applicable) \
                        and self.admits(s, b, goal) and not self.undoes_skill(s, b) and \
                        (applicable or not self._circular(goal, ground)):
                    ready = applicable and all(self.holds(c) for c in ground)
                    extra = [v for k, v in b.items() if k not in b0]
                    apart = len(set(extra)) == len(extra) and not fixed & set(extra)
                    ranked.append(((not ready,), (not apart, binding_key(b)), b, ground))
            if ranked:
                break
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
                ground = grounded(clause.relations, b)
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
                ground = grounded(list(conj.conds), b)
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

    def _candidates(self, percepts: list, conds: list, b0: dict, anything: bool = False,
                    shared: bool = False) -> list[dict]:
        """Bindings of the clause's variables: its :percepts matched, then any variable left
        taken from beliefs matching a positive condition (in written order), and, with
        ``anything`` (a concept's or a conjunction's relations, when the beliefs give no
        way), also each variable from the objects perceived (``(on ?x A)`` with nothing on
        A: each block may be put there; ``Task.impossible`` then leaves out what nothing can
        make true). A variable the goal does not fix names an object of its own: one the goal
        or another such variable names is not taken (no (unstack B B) to clear B), unless
        ``shared``: a skill none of whose bindings keeps its objects apart may share them
        (TPP's (unload G T D L0 L1 L0 L1): ``next`` fixes two level pairs, both the same)."""
        sols = list(islice(solve(percepts, b0, self.pidx, self.store), MAX_BINDINGS)) \
            if percepts else [b0]
        lits = [c for c in conds if isinstance(c, Literal) and not c.negated]
        out: dict = {}
        fixed = set(b0.values())
        for b in sols:
            for nb in self._bind_rest(lits, b, anything):
                extra = [v for k, v in nb.items() if k not in b0]
                if shared or (len(set(extra)) == len(extra) and not fixed & set(extra)):
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


class WayFilters:
    """Needs the Task's program, effects, protected, refused, conflicts, holds and _shows."""

    def undoes_skill(self, s: Skill, b: dict) -> bool:
        """True when skill ``s`` under ``b`` would act to undo a protected goal (recorded in
        ``refused``, for the failure's reason)."""
        if not self.protected or s.kind != "primitive":
            return False
        try:
            actions = [Action(a.name, tuple(evaluate(x, b) for x in a.args)) for a in s.actions]
        except EvalError:
            return False
        hit = undone_goal(self.effects, self.protected, actions)
        if hit is not None:
            gid, text, lit = hit
            self.conflicts[gid] = text
            self.refused.append(f"{self._shows(s, b)} would undo {lit} of goal {gid} {text}, "
                                "which holds and comes first")
        return hit is not None

    def _circular(self, goal: Literal, ground: list) -> bool:
        """True when a false condition of a way (or a false part of its definition) can only be
        achieved through ``goal`` itself, a landmark of it (agents/lang/solving/landmarks.py):
        clearing B3 by lifting B6 off it, when B6 is not on B3, would first need B6 put there,
        which needs (clear B3). Such a way is not chained off."""
        goal_key = key(goal)
        for c in ground:
            if not isinstance(c, Literal) or c.negated or self.holds(c):
                continue
            for r in (c, *self._definition(c)):
                if not r.variables() and not self.holds(r) and \
                        goal_key in landmarks(self, r):
                    return True
        return False

    def _definition(self, lit: Literal) -> list[Literal]:
        """The positive relations of ``lit``'s single defining clause, bound by its head."""
        clauses = self.program.concepts.get(lit.pred, ())
        if len(clauses) != 1:
            return []
        b = unify_head(clauses[0].head, lit, {})
        return [] if b is None else [ground_literal(r, b) for r in clauses[0].relations
                                     if not r.negated]
