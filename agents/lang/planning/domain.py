"""The planning domain of a program (seed 003, PRODIGY): its operators as a program of their
own (so the means-ends problem solver's chaining code, agents/lang/solving/task.py, chains
on them), its request rules and control rules; operator instances as plan steps, their
projection onto a state (STRIPS: the deletes, then the adds), and the travel metric from
the world's distance percepts. Pure."""

from __future__ import annotations

from dataclasses import replace
from itertools import islice

from ..core.arith import evaluate
from ..core.errors import EvalError
from ..core.matcher import ground, match_fact, match_percept, solve, subst, unify_head
from ..core.program import Program, Skill
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Literal, Var
from ..solving.state import Alternative, literal
from .state import PlanStep
from .syntax import ControlRule, OperatorSpec, RequestSpec, Travel, between_vars

UNREACHABLE = 10_000.0   # [m] the cost of going where no route is known


class Domain:
    """The fixed part of planning for one program: ``operators`` (OperatorSpec, in program
    order), ``program`` (the program with the operators' skills as its skills, numbered in
    that order), ``requests``, ``rules`` (ControlRule), ``travel`` (or None) and
    ``model_preds`` (predicates only the planner knows: no concept defines them)."""

    def __init__(self, program: Program):
        self.operators: tuple[OperatorSpec, ...] = tuple(program.sections.get("operators", ()))
        by_pred: dict[str, list[Skill]] = {}
        skills = []
        for n, op in enumerate(self.operators):
            group = by_pred.setdefault(op.head.pred, [])
            skill = replace(op.skill, index=len(group) + 1, number=n)
            group.append(skill)
            skills.append(skill)
        self.program = replace(program, skills=tuple(skills),
                               skills_by_pred={k: tuple(v) for k, v in by_pred.items()})
        self.requests: tuple[RequestSpec, ...] = tuple(program.sections.get("requests", ()))
        rules = program.sections.get("control-rules", ())
        self.rules = tuple(r for r in rules if isinstance(r, ControlRule))
        self.travel: Travel | None = next((r for r in rules if isinstance(r, Travel)), None)
        self.model_preds = frozenset(p for p in program.arity if p not in program.concepts)

    def step(self, way: Alternative, achieves: str, state: FactStore) -> PlanStep:
        """The plan step of operator alternative ``way`` (chosen for ``achieves``); its place
        is where the robot is in ``state`` once its effects are applied."""
        op = self.operators[way.clause]
        b = {Var(k): v for k, v in way.bindings}
        after = project(state, tuple(str(ground(e, b)) for e in op.effects))
        return PlanStep(op.name, tuple(subst(a, b) for a in op.params), way.clause,
                        way.bindings, achieves, str(ground(op.head, b)), way.conditions,
                        tuple(str(ground(e, b)) for e in op.effects),
                        _commands(op.skill.actions, b), _commands(op.on_failure, b),
                        self.place(after))

    def place(self, state: FactStore) -> str:
        """Where the robot is in ``state`` (the travel :location's place), "" if unknown."""
        if self.travel is None:
            return ""
        loc = self.travel.location
        var = next(iter(loc.variables()))
        found = next(match_fact(loc, {}, state), None)
        return str(found[var]) if found else ""

    def carried(self, store: FactStore) -> int:
        """How many things the robot carries in ``store`` (instances of the travel
        :carrying literal; 0 when the program does not say)."""
        lit = self.travel.carrying if self.travel is not None else None
        return 0 if lit is None else sum(1 for _ in match_fact(lit, {}, store))

    def load_delta(self, step: PlanStep) -> int:
        """What ``step`` changes in what the robot carries: +1 for each :carrying instance
        its effects add, -1 for each they delete."""
        lit = self.travel.carrying if self.travel is not None else None
        if lit is None:
            return 0
        effects = [literal(e) for e in step.effects]
        return sum((-1 if e.negated else 1) for e in effects if e.pred == lit.pred)

    def still_applies(self, step: PlanStep, pidx: PerceptIndex) -> bool:
        """The step's :percepts still match under its bindings (who holds the item, where
        the person is): otherwise the plan was made for a world that changed."""
        pats = list(self.operators[step.clause].skill.percepts) \
            if step.clause < len(self.operators) else None
        if pats is None or self.operators[step.clause].name != step.name:
            return False
        b = {Var(k): v for k, v in step.bindings}
        return next(solve(pats, b, pidx, FactStore()), None) is not None

    def knowledge(self, goal: Literal, pidx: PerceptIndex, store: FactStore
                  ) -> tuple[str, ...]:
        """The facts the first matching request rule adds for a new request ``goal``."""
        for rule in self.requests:
            if (rule.head.pred, len(rule.head.args)) != (goal.pred, len(goal.args)):
                continue
            b0 = unify_head(rule.head, goal, {})
            if b0 is None:
                continue
            sol = next(solve([*rule.percepts, *rule.start], b0, pidx, store), None)
            if sol is not None:
                return tuple(str(ground(k, sol)) for k in rule.knowledge)
        return ()


def _commands(templates: tuple, b: dict) -> tuple[tuple, ...]:
    out = []
    for a in templates:
        try:
            out.append((a.name, *(evaluate(x, b) for x in a.args)))
        except EvalError:
            out.append((a.name, *(subst(x, b) for x in a.args)))
    return tuple(out)


def with_facts(store: FactStore, facts: tuple[str, ...]) -> FactStore:
    """``store`` plus ``facts`` (literal text), sharing the unchanged fact sets."""
    if not facts:
        return store
    table = dict(store.facts)
    for text in facts:
        lit = literal(text)
        table[lit.pred] = set(table.get(lit.pred, ())) | {lit.args}
    return FactStore(table)


def refresh(store: FactStore, old: tuple[str, ...], new: tuple[str, ...]) -> FactStore:
    """``store`` with the planner's facts ``old`` replaced by ``new`` (literal text)."""
    if old == new:
        return store
    gone = set(old) - set(new)
    return project(store, tuple(f"(not {f})" for f in sorted(gone)) + tuple(new))


def project(store: FactStore, effects: tuple[str, ...]) -> FactStore:
    """The state after effects (literal text): every negated one deleted (a variable in it
    matches any value), then every positive one added."""
    table = dict(store.facts)
    lits = [literal(e) for e in effects]
    for lit in lits:
        if lit.negated:
            pos = Literal(lit.pred, lit.args)
            gone = {tuple(subst(a, b) for a in lit.args)
                    for b in match_fact(pos, {}, FactStore({lit.pred: table.get(lit.pred,
                                                                                set())}))}
            table[lit.pred] = set(table.get(lit.pred, ())) - gone
    for lit in lits:
        if not lit.negated:
            table[lit.pred] = set(table.get(lit.pred, ())) | {lit.args}
    return FactStore(table)


class Metric:
    """Travel distances [m] from the percepts named by ``(travel ...)``: ``here[p]`` from the
    robot's position to place p, ``between(a, b)`` from place a to place b; UNREACHABLE
    where no route is known (a negative distance, or no percept); and ``capacity``, what the
    robot can carry (the :capacity percept), or None."""

    def __init__(self, travel: Travel | None, pidx: PerceptIndex):
        self.here: dict[str, float] = {}
        self.pairs: dict[tuple[str, str], float] = {}
        self.capacity: int | None = None   # how many things the robot can carry, if known
        if travel is None:
            return
        if travel.capacity is not None:
            c = between_vars(travel.capacity)[-1]
            sol = next(match_percept(travel.capacity, {}, pidx), None)
            if sol is not None and isinstance(sol.get(c), int | float):
                self.capacity = int(sol[c])
        a, b, d = between_vars(travel.between)
        for sol in islice(match_percept(travel.between, {}, pidx), 100_000):
            if isinstance(sol.get(d), int | float) and sol[d] >= 0:
                self.pairs[(str(sol[a]), str(sol[b]))] = float(sol[d])
        p, d = between_vars(travel.from_here)
        for sol in match_percept(travel.from_here, {}, pidx):
            if isinstance(sol.get(d), int | float) and sol[d] >= 0:
                self.here[str(sol[p])] = float(sol[d])

    def between(self, a: str, b: str) -> float:
        if a == b:
            return 0.0
        return self.pairs.get((a, b), self.pairs.get((b, a), UNREACHABLE))

    def from_here(self, p: str) -> float:
        return self.here.get(p, UNREACHABLE)

    def reachable(self, p: str) -> bool:
        return not p or p in self.here

    def move(self, cur: str | None, p: str) -> float:
        """From ``cur`` (None: the robot's position) to ``p`` ("" costs nothing)."""
        if not p:
            return 0.0
        return self.from_here(p) if cur is None else self.between(cur, p)

    def length(self, start: str, places: list[str]) -> float:
        """The length of a route through ``places`` from ``start`` [m] (unknown legs
        skipped)."""
        total, cur = 0.0, start
        for p in places:
            if p and cur and p != cur:
                leg = self.between(cur, p)
                total += leg if leg < UNREACHABLE else 0.0
            cur = p or cur
        return round(total, 3)
