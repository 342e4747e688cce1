"""Which instances of a literal some skill or concept can make true (docs/language.md, "Goals
with variables: which instances"): the solver binds a conjunction's or a concept's free
variables only to objects that can make its literals true, and the executive leaves out a
goal's instances that nothing can (``(on D D)`` among ``(on D ?x)``'s).

An instance is **impossible** when its predicate has ways to be made true (primitive skills,
or concept clauses with :relations) and none of them can for this instance: no skill whose
head matches it has :percepts that match, or every one that does has a start that contradicts
itself, and no concept clause decomposes it into relations that are consistent and possible in
turn. A start contradicts itself when its conditions, expanded through the definitions of
concepts with a single clause, require a literal and its negation: ``(stackable A A)`` needs
``(holding A)`` and ``(clear A)``, whose definition says ``(not (holding A))``. A predicate
with no way at all (a concept only the world makes true, such as a traffic light's colour) is
never judged impossible: the world may make it hold.

Pure: it reads the program and one cycle's percepts and beliefs."""

from __future__ import annotations

from ..core.matcher import ground, solve, unify_head
from ..core.program import Program
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, Var
from ..reading.goals import instances

MAX_EXPAND = 3     # levels of single-clause definitions expanded to find a contradiction
MAX_DEPTH = 3      # levels of concept decomposition judged for possibility
MAX_MATCHES = 64   # percept matches examined per skill or clause, and bindings made of
                   # objects [matches]
MAX_COST = 40      # levels of a plan regressed to estimate its cost [levels]
MAX_REFUSED = 12   # ways left out noted for a failure's reason [ways]


class Reach:
    """The possibility of instances in one situation (``program``, ``pidx``, ``store``),
    each judged once."""

    def __init__(self, program: Program, pidx: PerceptIndex, store: FactStore):
        self.program = program
        self.pidx = pidx
        self.store = store
        self._memo: dict[tuple[Literal, int], bool] = {}

    def holds(self, lit: Literal) -> bool:
        return not lit.variables() and lit.args in self.store.get(lit.pred)

    def possible(self, lit: Literal, depth: int = MAX_DEPTH) -> bool:
        """False when ``lit`` (positive) is impossible (see the module docstring); a literal
        with variables, one that holds, or one whose predicate has no way is possible."""
        if lit.negated or lit.variables() or self.holds(lit):
            return True
        key = (Literal(lit.pred, lit.args), depth)
        hit = self._memo.get(key)
        if hit is None:
            self._memo[key] = True   # (a cycle through definitions is not a contradiction)
            hit = self._memo[key] = self._judge(lit, depth)
        return hit

    def _judge(self, lit: Literal, depth: int) -> bool:
        skills = [s for s in self.program.skills_for(lit.pred) if s.kind == "primitive"]
        clauses = [c for c in self.program.concepts.get(lit.pred, ()) if c.relations]
        if not skills and not clauses:
            return True
        for s in skills:
            b0 = unify_head(s.head, lit, {})
            if b0 is None:
                continue
            for b in _matches(list(s.percepts), b0, self):
                conds = [ground(c, b) for c in (*s.start, *s.requires)
                         if isinstance(c, Literal)]
                if self.consistent(conds):
                    return True
        if depth <= 0:
            return bool(clauses)
        for clause in clauses:
            b0 = unify_head(clause.head, lit, {})
            if b0 is None:
                continue
            for b in _matches(list(clause.percepts), b0, self):
                rels = [ground(r, b) for r in clause.relations]
                if self.consistent(rels) and all(
                        self.possible(r, depth - 1) for r in rels
                        if not r.negated and not r.variables()):
                    return True
        return False

    def consistent(self, conds: list[Literal]) -> bool:
        """False when ``conds``, expanded through single-clause definitions, require a ground
        literal and a negation that matches it (a negation's variables that nothing else in
        its clause binds match anything: ``(not (on ?other A))`` excludes every ``(on X A)``)."""
        pos: set[Literal] = set()
        neg: list[Literal] = []
        for c in conds:
            self._expand(c, {}, MAX_EXPAND, pos, neg, frozenset(c.variables()))
        return not any(unify_head(n, p, {}) is not None for n in neg for p in pos
                       if n.pred == p.pred and len(n.args) == len(p.args))

    def _expand(self, lit: Literal, b: dict, depth: int, pos: set, neg: list,
                bound: frozenset) -> None:
        g = ground(lit, b)
        if g.negated:
            free = g.variables() - bound
            if g.variables() == free:   # a wildcard negation, or a ground one
                neg.append(Literal(g.pred, g.args))
            return
        if g.variables():
            return
        pos.add(Literal(g.pred, g.args))
        clauses = self.program.concepts.get(g.pred, ())
        if depth <= 0 or len(clauses) != 1 or not clauses[0].relations:
            return
        clause = clauses[0]
        b1 = unify_head(clause.head, g, {})
        if b1 is None:
            return
        shared = set()   # a clause's variables bound outside its negations
        for x in (*clause.percepts, *clause.tests):
            shared |= x.variables()
        for r in clause.relations:
            if not r.negated:
                shared |= r.variables()
        for r in clause.relations:
            rb = ground(r, b1)
            if r.negated:
                if rb.variables() & shared:
                    continue   # bound elsewhere in the clause: not every object
                neg.append(Literal(rb.pred, rb.args))
            else:
                self._expand(rb, {}, depth - 1, pos, neg, frozenset())


def _matches(percepts: list, b0: dict, reach: Reach) -> list[dict]:
    """The matches of a clause's :percepts under ``b0`` (``[b0]`` without any)."""
    if not percepts:
        return [b0]
    out = []
    for b in solve(percepts, b0, reach.pidx, reach.store):
        out.append(b)
        if len(out) >= MAX_MATCHES:
            break
    return out


class BindingChoice:
    """A part of Task (agents/lang/solving/task.py): needs its program, pidx, store, holds,
    refused and ``_reach``."""

    @property
    def reach(self) -> Reach:
        """Which instances some skill or concept can make true (agents/lang/solving/
        bindings.py), judged once each this cycle."""
        if self._reach is None:
            self._reach = Reach(self.program, self.pidx, self.store)
        return self._reach

    def impossible(self, conds: list) -> str:
        """Why the ground conditions ``conds`` of a way can never all hold ("" when they may):
        they contradict one another, or one that does not hold is an instance nothing can
        make true (``(on A A)``; agents/lang/solving/bindings.py)."""
        lits = [c for c in conds if isinstance(c, Literal)]
        if not self.reach.consistent(lits):
            return f"{' '.join(map(str, lits))} contradict one another"
        bad = next((c for c in lits if not c.negated and not self.holds(c)
                    and not self.reach.possible(c)), None)
        return "" if bad is None else f"no skill or concept can make {bad} true"

    def _possible(self, ground: list, way: str) -> bool:
        """Whether ``ground`` may all hold; if not, why ``way`` was left out is noted for
        the failure's reason (``refused``)."""
        why = self.impossible(ground)
        if why and len(self.refused) < MAX_REFUSED:
            self.refused.append(f"left out {way}: {why}")
        return not why

    def _any(self, lits: list[Literal], b: dict) -> list[dict]:
        """``b`` extended with every object perceived for each variable of ``lits`` it
        leaves free (at most MAX_MATCHES)."""
        out = [b]
        for v in dict.fromkeys(v for lit in lits for v in lit.args
                               if isinstance(v, Var) and v not in b):
            out = [{**x, v: o} for x in out for o in objects(self.pidx)][:MAX_MATCHES]
        return out


def cheapest(task, ranked: list) -> list:
    """The bindings of an existential clause or conjunction (``ranked``: (rank, key,
    binding, ground conditions)) best first, at most ``task.per_clause``: fewest actions
    first, estimated by ``cost``, then ``rank``: (on D C) before (on D A) when C is clear and
    A is under two blocks."""
    keyed = sorted(((sum(cost(task, str(c)) for c in r[3]), r[0], r[1]), r) for r in ranked)
    return [r for _, r in keyed[:task.per_clause]]


def cost(task, text: str, depth: int = MAX_COST, on_path: frozenset = frozenset()) -> int:
    """The subgoals the solver's own plan for condition ``text`` would push: 0 when it holds,
    else 1 and those of the first way it would chain off (an executable skill first), as
    agents/lang/solving/ordering.py's ``needs`` regresses it; a negation, a test or a loop
    counts 1."""
    if task.holds(text):
        return 0
    lit = task.subgoal(text)
    if lit is None or depth <= 0 or text in on_path:
        return 1
    key = ("cost", text)
    if key not in task.memo:
        ways = sorted(task.alternatives(lit, applicable=True),
                      key=lambda w: not all(task.holds(c) for c in w.conditions))
        task.memo[key] = 1 + (sum(cost(task, c, depth - 1, on_path | {text})
                                  for c in ways[0].conditions) if ways else 0)
    return task.memo[key]


def objects(pidx: PerceptIndex) -> list:
    """The ids of the objects perceived this cycle (numbers first, then by value), the values
    a variable that no belief binds may take."""
    return sorted({pid for (_, pid) in pidx.by_id}, key=lambda v: (isinstance(v, str), v))



def never_true(program: Program, goal, pidx: PerceptIndex, store: FactStore) -> list:
    """The instances of ``goal`` (a literal with variables: "every instance", docs/language.md)
    this cycle that do not hold and that no skill or concept can make true, such as
    ``(on D D)`` among ``(on D ?x)``'s; empty for a conjunction or a goal without variables
    (a user wrote those)."""
    if not isinstance(goal, Literal) or not goal.variables():
        return []
    reach = Reach(program, pidx, store)
    return [i for i in instances(goal, program, pidx) if not reach.possible(i)]


def instances_warning(goal, bad: list) -> str:
    """One line for ``teleo check`` and ``teleo goal post``: ``goal``'s instances include
    ``bad``, which nothing can make true; "" when ``bad`` is empty."""
    if not bad:
        return ""
    shown = " ".join(map(str, bad[:3])) + (f" and {len(bad) - 3} more" if len(bad) > 3 else "")
    return (f"{goal} means every instance, and its instances include {shown}, which no skill "
            f"or concept can make true (left out when the agent pursues it); for some "
            f"instance, write (and {goal})")
