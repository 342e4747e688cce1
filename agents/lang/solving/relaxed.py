"""A delete-relaxed estimate of how far a literal is from the current situation, to
order the solver's choices among bindings of a skill (which truck, which airport): the
primitive skills of the program applied forward from what holds now, each as soon as its start
holds, their undoing ignored; a literal's level is the number of such rounds before it first
holds (0: it holds now; None: never, so no binding that needs it is chained off).

It is an ordering heuristic over the program's own skills, not a planner: no plan is kept or
executed, the solver still chains backwards one decision a cycle (agents/lang/solving/search.py).

Only for programs where it is sound: every concept that a primitive skill's head or start
names is read from percepts alone (no :relations, no :tests), as the programs `teleo pddl
program` writes are; negated start conditions and tests are ignored (that only makes more
reachable). For any other program (programs/blocks.tlp defines (stackable ?b ?to) by
relations) ``Relaxed.available`` is False and the solver ranks as before. Pure."""

from __future__ import annotations

from collections import defaultdict
from itertools import islice

from ..core.matcher import solve, unify_head
from ..core.program import Program
from ..core.terms import Literal, Var
from ..execution.effects import Effects
from .landmarks import key

MAX_LEVELS = 64        # rounds of forward application [rounds]
MAX_GROUND = 20000     # ground skill applications per round before giving up [applications]
MAX_DOMAIN = 4096      # objects one percept pattern may bind [objects]

Fact = tuple


class Relaxed:
    """The levels of every literal reachable from the situation of ``task`` (a Task: program,
    pidx, store), computed on first use."""

    def __init__(self, task) -> None:
        self.task = task
        self.skills = _eligible(task.program)
        self.available = self.skills is not None
        self._level: dict[Fact, int] | None = None

    def level(self, lit: Literal) -> int | None:
        """Rounds before the ground literal ``lit`` first holds (0 now), None if never."""
        if self._level is None:
            self._level = self._compute()
        return self._level.get((lit.pred, *lit.args))

    def _compute(self) -> dict[Fact, int]:
        store, pidx = self.task.store, self.task.pidx
        preds = {s.head.pred for s in self.skills} | {
            c.pred for s in self.skills for c in s.start}
        level: dict[Fact, int] = {}
        reached = _Index()
        for p in preds:
            for args in store.get(p):
                level[(p, *args)] = 0
                reached.add(p, tuple(args))
        domains = {}
        for s in self.skills:
            for pat in s.percepts:
                if isinstance(pat.id, Var) and (pat.type, pat.id, pat.attrs) not in domains:
                    domains[(pat.type, pat.id, pat.attrs)] = {
                        b[pat.id] for b in islice(solve([pat], {}, pidx, store), MAX_DOMAIN)
                        if pat.id in b}
        doms = [_domains(s, domains) for s in self.skills]
        delta = _Index()
        for p, facts in reached.facts.items():
            for args in facts:
                delta.add(p, args)
        for k in range(1, MAX_LEVELS + 1):
            new: dict[Fact, int] = {}
            work = 0
            for s, dom in zip(self.skills, doms, strict=True):
                if dom is None:
                    continue
                for b in _seminaive(s.start, reached, delta, dom, k == 1):
                    work += 1
                    if work > MAX_GROUND:
                        return level   # too big to estimate: what was found so far
                    for full in _open(s, b, dom):
                        head = (s.head.pred, *(full.get(a, a) if isinstance(a, Var) else a
                                               for a in s.head.args))
                        if head not in level and head not in new:
                            new[head] = k
            if not new:
                break
            delta = _Index()
            for f in new:
                level[f] = k
                reached.add(f[0], f[1:])
                delta.add(f[0], f[1:])
        return level


def _eligible(program: Program):
    """The primitive skills, each with its start as positive literals only, or None when a
    skill's head or start names a concept not read from percepts alone."""
    flat = {p for p, clauses in program.concepts.items()
            if all(not c.relations and not c.tests for c in clauses)}
    out = []
    for s in program.skills:
        if s.kind != "primitive":
            continue
        conds = [c for c in (*s.start, *s.requires) if isinstance(c, Literal)]
        if s.head.pred not in flat or any(c.pred not in flat for c in conds if not c.negated):
            return None
        out.append(_Skill(s.head, s.percepts, tuple(c for c in conds if not c.negated)))
    return out or None


class _Index:
    """Facts by predicate (``get``), and by predicate, argument position and value, so that
    a join looks only at the facts that agree with what is bound already (``matching``): the
    same bindings as a scan of every fact of the predicate, found without the scan."""

    __slots__ = ("facts", "by")

    def __init__(self) -> None:
        self.facts: dict[str, set[tuple]] = defaultdict(set)
        self.by: dict[tuple, set[tuple]] = defaultdict(set)

    def add(self, pred: str, args: tuple) -> None:
        if args in self.facts[pred]:
            return
        self.facts[pred].add(args)
        for i, v in enumerate(args):
            self.by[(pred, i, v)].add(args)

    def get(self, pred: str, default=None):
        return self.facts.get(pred, default)

    def matching(self, lit: Literal, b: dict):
        """The facts of ``lit``'s predicate whose argument at the first position ``lit`` (under
        ``b``) fixes has that value; all of them when it fixes none."""
        for i, a in enumerate(lit.args):
            if not isinstance(a, Var):
                return self.by.get((lit.pred, i, a), ())
            if a in b:
                return self.by.get((lit.pred, i, b[a]), ())
        return self.facts.get(lit.pred, ())


class _Skill:
    __slots__ = ("head", "percepts", "start")

    def __init__(self, head, percepts, start) -> None:
        self.head, self.percepts, self.start = head, percepts, start


def _domains(s: _Skill, domains: dict) -> dict | None:
    """Each variable of ``s`` with percept patterns -> the objects all of them allow; None
    when one allows none."""
    out: dict = {}
    for p in s.percepts:
        if isinstance(p.id, Var):
            d = domains[(p.type, p.id, p.attrs)]
            out[p.id] = d if p.id not in out else out[p.id] & d
            if not out[p.id]:
                return None
    return out


def _seminaive(lits: tuple[Literal, ...], reached: dict, delta: dict, dom: dict, first: bool):
    """Bindings under which every literal of ``lits`` is reached and (after the first round)
    at least one was reached in the last round."""
    if not lits:
        if first:
            yield {}
        return
    for i in range(len(lits)):
        if not delta.get(lits[i].pred):
            continue
        order = (lits[i], *lits[:i], *lits[i + 1:])
        sources = [delta] + [reached] * (len(lits) - 1)
        yield from _join(order, sources, {}, dom)


def _join(lits: tuple[Literal, ...], sources: list, b: dict, dom: dict):
    """Bindings under which each literal of ``lits`` is among its source's facts, every
    variable in its domain."""
    if not lits:
        yield b
        return
    lit = lits[0]
    for args in sources[0].matching(lit, b):
        if len(args) != len(lit.args):
            continue
        nb = dict(b)
        for a, v in zip(lit.args, args, strict=True):
            if isinstance(a, Var):
                if nb.setdefault(a, v) != v or (a in dom and v not in dom[a]):
                    break
            elif a != v:
                break
        else:
            yield from _join(lits[1:], sources[1:], nb, dom)


def _open(s: _Skill, b: dict, dom: dict):
    """``b`` completed over the head's variables the start leaves open, from their domains."""
    open_ = [v for v in dict.fromkeys(a for a in s.head.args if isinstance(a, Var))
             if v not in b]
    if not open_:
        yield b
        return
    if any(v not in dom for v in open_):
        return
    yield from _product([(v, sorted(dom[v], key=str)) for v in open_], b)


def _product(choices: list, b: dict):
    if not choices:
        yield b
        return
    (v, values), rest = choices[0], choices[1:]
    for x in values:
        yield from _product(rest, {**b, v: x})


class InferredEffects(Effects):
    """The program's effect model (agents/lang/execution/effects.py), and for a program the
    relaxed estimate applies to that states no :effects (its concepts read from percepts, so
    nothing says what an action undoes) what achieving a literal undoes as a STRIPS
    operator's start implies: the start conditions of every primitive skill that achieves
    it which some primitive skill achieves (fluents, not static facts such as (in-city ?l
    ?c)), those common to all such skills, and only those about the same thing as the head
    (``_about``: (*depart ?f ?p) undoes (boarded ?p), not (lift-at ?f)). In the PDDL Blocks
    World, (on ?x ?y) by (*stack ?x ?y) undoes (holding ?x) and (clear ?y). An estimate for
    ordering the solver's choices (agents/lang/solving/ordering.py), as the seed's skills
    state their effects."""

    def __init__(self, program: Program, base: Effects) -> None:
        super().__init__(program)
        self.base = base
        skills = _eligible(program)
        prims = [s for s in program.skills if s.kind == "primitive"]
        # a program that states its effects (:effects, as teleo pddl program writes) needs
        # no inference: the base model has them
        self.skills = prims if skills and not any(s.effects for s in prims) else []
        self.fluents = {s.head.pred for s in self.skills}
        self._inferred: dict[Literal, tuple[Literal, ...]] = {}

    def undoes(self, e: Literal) -> tuple[Literal, ...]:
        hit = self._inferred.get(e)
        if hit is None:
            hit = tuple(dict.fromkeys((*self.base.undoes(e), *self._implied(e))))
            if len(self._inferred) < MAX_DOMAIN:
                self._inferred[e] = hit
        return hit

    def _implied(self, e: Literal) -> list[Literal]:
        common: dict[str, Literal] | None = None
        for s in self.skills:
            if s.head.pred != e.pred or len(s.head.args) != len(e.args):
                continue
            b = unify_head(s.head, e, {})
            if b is None:
                continue
            mine = {}
            for c in (*s.start, *s.requires):
                if isinstance(c, Literal) and not c.negated and c.pred in self.fluents \
                        and _about(c, s.head):
                    p = Literal(c.pred, tuple(b.get(a, a) if isinstance(a, Var) else a
                                              for a in c.args))
                    if p != e:
                        mine[key(p)] = p
            common = mine if common is None else {k: v for k, v in common.items()
                                                  if k in mine}
        return list((common or {}).values())


def _about(c: Literal, head: Literal) -> bool:
    """Whether the start condition ``c`` speaks of what ``head`` does: the same predicate (a
    place left for another), the head's first argument (its subject: (holding ?x) for (on ?x
    ?y)), or nothing but the head's arguments ((clear ?y) for (on ?x ?y))."""
    args = [a for a in c.args]
    return c.pred == head.pred or (bool(head.args) and head.args[0] in args) or \
        (bool(args) and all(a in head.args for a in args))
