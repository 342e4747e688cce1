"""The order in which a conjunctive goal's conjuncts are pursued, by goal regression
over the program: achieve first what achieving another conjunct would not undo.

For each unsatisfied conjunct h, ``needs`` regresses the solver's own plan from the current
situation (the first way ``Task.alternatives`` ranks at each level, as the search would choose
it; for a subgoal that holds, what it holds by), and ``landmarks`` the conditions that every
way of achieving h passes through. A conjunct g *threatens* h when achieving g would make one
of h's needs false (agents/lang/execution/effects.py: ``(on A B)`` makes ``(clear B)`` false). Then:

1. a conjunct that threatens nobody may be pursued (building a tower from its base: ``(on B
   C)`` before ``(on A B)``, since ``(on A B)`` would undo ``(clear B)``, which ``(on B C)``
   needs to pick B up); among them, one that one executable action achieves now comes first
   (a block in the hand goes straight to its place), then the one being worked on, then the
   written order;
2. if every one threatens another, and g's threats are to needs that are not landmarks (they
   come from how the world happens to be, not from what h is), the part of h's plan that needs
   the threatened condition is done first: the nearest unsatisfied goal above it in h's plan
   (the Sussman anomaly: C on A, goal (and (on A B) (on B C)): (on B C) would cover C, which
   (on A B)'s plan must clear to free A, so (clear A) comes first);
3. otherwise the unsatisfied conjuncts in written order (the search may then undo a conjunct for
   a while; the MAX_PUSHES rule and the loop watch keep that from going on for ever).

A part of a plan to be done first (2.) that one action achieves now is done now even when some
conjunct is free (B1 on B2, both to end on the table's side of things: lifting B1 off B2 first
lets B3 go straight onto it later), unless it puts back what the last cycle's actions undid
(``Task.undone``: a crate lifted for the truck is not dropped where it was for another
conjunct's plan); a part just done goes on with the conjunct whose plan would not first
put it back.

The threats are found by index (``Threats``), not pair by pair (``threatens``; n conjuncts
whose plans need k literals each: n * n * k checks, 285,000 for visitall's 144 cells): the
needs by predicate and first constant argument, so that a pattern meets only the needs it can
cover; the conjuncts by what achieving them undoes (their *shape*: every cell of visitall
undoes ``(at-robot ?from)``), the needs a shape threatens found once for all its conjuncts;
what a conjunct achieves with it (``(at-robot X)``) excuses a few, found by an index of the
goals the needs are for; a negated need, which depends on the conjunct, is checked per
conjunct. The answers are those of the pairwise check (tests/lang/solving/
test_ordering_threats.py keeps it as the reference).

Pure; regressions (agents/lang/solving/landmarks.py, ``needs``) are kept for the cycle in
``Task.memo``, agendas across cycles by situation (a cycle spent deciding leaves the situation
as it was) in ``Task.shared``."""

from __future__ import annotations

from ..core.terms import Literal, Var
from ..execution.effects import undone_by
from .landmarks import (
    key,
    landmarks,
    needs,
    one_step,
    plan_depth,
)
from .state import condition, literal, pushable
from .task import Task

MAX_SHARED = 64    # agendas kept across cycles [agendas]


def agenda(task: Task, conds: tuple[str, ...], current: str = "",
           above: tuple[str, ...] = ()) -> list[str]:
    """The literals to pursue for a conjunction with ground ``conds``, best first (see the
    module docstring); ``current``: the one being worked on; ``above``: the goals on the
    stack above (a skill's start: its plans go no way back through them). Empty when
    nothing can be pushed (every conjunct holds, or one that does not is a negation or a
    test)."""
    key = ("agenda", task.situation, conds, current, task.protected, above, task.undone)
    undone = task.undone
    if key in task.shared:
        return task.shared[key]
    unsat, plans, free, promote, later, now = _parts(task, conds, above)
    if current and current not in conds:   # a part of a conjunct's plan, done first: that
        # conjunct's plan goes on (not another's, which would move again what the
        # first would have put in its place): of those free, the one whose plan needs it
        # nearest
        # (not one whose plan would first put back what the step for it just undid:
        # a crate lifted for a truck, to be dropped where it was for another conjunct)
        cur = literal(current)
        current = min((h for h in [*free, *unsat] if cur in plans[h]),
                      key=lambda h: (h not in free, _restores(plans[h][cur], undone),
                                     plan_depth(plans[h], cur)),
                      default=current)
    if free:
        now = now + [p for p in promote if p not in now and not _restores(p, undone)
                and one_step(task, p)]
        out = now + [g for g in free if g == current and g not in now] + \
            [g for g in free if g not in now and g != current]
        out = [g for g in out if g not in later] + [g for g in out if g in later]
    elif promote:
        out = list(promote)
    else:
        out = unsat
    if len(task.shared) >= MAX_SHARED:
        task.shared.clear()
    task.shared[key] = out
    return out


def _parts(task: Task, conds: tuple[str, ...], above: tuple[str, ...]) -> tuple:
    """What ``agenda`` orders by, whatever the conjunct worked on and the last cycle's
    actions: the unsatisfied conjuncts, their plans, those free, the parts of plans to be done
    first, those left for later, and the free ones one action achieves now (kept across
    cycles by situation, like the agendas)."""
    key = ("parts", task.situation, conds, task.protected, above)
    if key in task.shared:
        return task.shared[key]
    unsat = [c for c in conds if pushable(condition(c)) and not task.holds(c)]
    plans = {h: needs(task, h, above) for h in unsat}
    threats = Threats(task, unsat, plans)
    # achieving a conjunct that another undoes outright is left for after it (the movie is
    # rewound, which resets the counter, before the counter is reset); the one that undoes it
    # is not held back for that (achieving it first is the way round)
    free: list[str] = []
    promote: dict[str, None] = {}
    for g in unsat:
        verdict = threats.verdict(g)
        if verdict == FREE:
            free.append(g)
        elif verdict == PROMOTE:
            threats.promote(g, promote)
    out = unsat, plans, free, promote, threats.later, [g for g in free if one_step(task, g)]
    if len(task.shared) >= MAX_SHARED:
        task.shared.clear()
    task.shared[key] = out
    return out


def _restores(goal: str, undone: tuple[Literal, ...]) -> bool:
    """Whether ``goal`` (a goal of a plan; "" for none) is what the last cycle's actions
    undid (``undone``): achieving it first would go straight back."""
    return bool(goal and undone) and undone_by(literal(goal), undone)


FREE, LANDMARK, PROMOTE = "free", "landmark", "promote"


def _index_key(p: Literal) -> tuple:
    """The bucket a pattern's instances are found in: its first constant argument, if any."""
    for k, a in enumerate(p.args):
        if not isinstance(a, Var):
            return (p.pred, len(p.args), k, a)
    return (p.pred, len(p.args))


def _buckets(lit: Literal) -> list[tuple]:
    """Every bucket a ground literal is in (``_index_key`` of the patterns that may cover it)."""
    return [(lit.pred, len(lit.args)),
            *((lit.pred, len(lit.args), k, a) for k, a in enumerate(lit.args))]


class Threats:
    """The threats among the unsatisfied conjuncts ``unsat`` to the plans ``plans``
    (``ordering.needs`` of each), answering as ``threatens`` pair by pair would."""

    def __init__(self, task, unsat: list[str], plans: dict[str, dict[Literal, str]]):
        self.task = task
        self.unsat = list(dict.fromkeys(unsat))
        self.entries = [(h, need, above) for h in self.unsat
                        for need, above in plans[h].items()]   # in the pairwise order
        self.positive: dict[tuple, list[int]] = {}   # ground positive needs by bucket
        self.negative: dict[tuple, list[int]] = {}   # negated needs by (pred, arity)
        for i, (_, need, _) in enumerate(self.entries):
            if need.negated:
                self.negative.setdefault((need.pred, len(need.args)), []).append(i)
            elif not need.variables():
                for k in _buckets(need):
                    self.positive.setdefault(k, []).append(i)
        self.goals = {h: literal(h) for h in self.unsat}
        self.undone = {h: task.effects.undoes(lit) for h, lit in self.goals.items()}
        self.later = self._later()
        self._shapes: dict[tuple, _Shape] = {}
        self._keys: dict[Literal, str] = {}
        self._excused: dict[str, set[int]] = {}

    @staticmethod
    def _covered(patterns: tuple[Literal, ...], index: dict, items) -> list[int]:
        """The indices in ``index`` (``items`` their literals) ``patterns`` cover, sorted."""
        out = {i for p in patterns for i in index.get(_index_key(p), ())
               if undone_by(items(i), (p,))}
        return sorted(out)

    def _later(self) -> set[str]:
        """The conjuncts another one undoes outright (``agenda``'s ``later``)."""
        members: dict[tuple, list[str]] = {}
        for g in self.unsat:
            members.setdefault(self.undone[g], []).append(g)
        index: dict[tuple, list[int]] = {}
        for j, h in enumerate(self.unsat):
            for k in _buckets(self.goals[h]):
                index.setdefault(k, []).append(j)
        out: set[str] = set()
        for undone, gs in members.items():
            for j in self._covered(undone, index, lambda j: self.goals[self.unsat[j]]):
                h = self.unsat[j]
                if len(gs) > 1 or gs[0] != h:
                    out.add(h)
        return out

    def _kept(self, i: int) -> bool:
        """Whether entry ``i`` counts as a threat at all: a conjunct that is left for later
        is not threatened by its being undone outright."""
        h, need, above = self.entries[i]
        return not (h in self.later and need == self.goals[h] and not above)

    def _shape(self, g: str) -> _Shape:
        """The threats of the conjuncts that undo what ``g`` undoes, before excuses."""
        undone = self.undone[g]
        hit = self._shapes.get(undone)
        if hit is None:
            found = [i for i in self._covered(undone, self.positive,
                                              lambda i: self.entries[i][1]) if self._kept(i)]
            hit = self._shapes[undone] = _Shape(found, self.entries)
        return hit

    def _excuses(self, g: str, shape: _Shape) -> set[int]:
        """The entries of ``shape`` whose goal achieving ``g`` achieves too."""
        hit = self._excused.get(g)
        if hit is None and not shape.above_lits:
            return set()   # (nothing to excuse: what ``g`` achieves with it is not asked)
        if hit is None:
            made = tuple(self.task.effects.achieved_with(self.goals[g]))
            hit = self._excused[g] = set(self._covered(
                made, shape.by_above, lambda i: shape.above_lits[i]))
        return hit

    def _negated(self, g: str) -> list[int]:
        """The entries (negated needs) achieving ``g`` threatens: those ``g`` is an instance of."""
        lit = self.goals[g]
        return [i for i in self.negative.get((lit.pred, len(lit.args)), ())
                if self.entries[i][0] != g and self._kept(i)
                and undone_by(lit, (Literal(self.entries[i][1].pred, self.entries[i][1].args),))]

    def _all(self, g: str, negs: list[int]) -> list[tuple[str, Literal, str]]:
        shape = self._shape(g)
        excused = self._excuses(g, shape)
        found = sorted({*(i for i in shape.found if i not in excused), *negs})
        return [self.entries[i] for i in found if self.entries[i][0] != g]

    def verdict(self, g: str) -> str:
        """FREE when achieving ``g`` threatens no other conjunct's plan, LANDMARK when one of
        its threats is to a landmark of that conjunct, else PROMOTE (``agenda``)."""
        negs = self._negated(g)
        if negs:
            threats = self._all(g, negs)
            if not threats:
                return FREE
            return LANDMARK if any(self._landmark(h, need) for h, need, _ in threats) \
                else PROMOTE
        shape = self._shape(g)
        excused = self._excuses(g, shape)

        def counts(i: int) -> bool:
            return self.entries[i][0] != g and i not in excused

        if not any(counts(i) for i in shape.found):
            return FREE
        if any(counts(i) for i in shape.hits):
            return LANDMARK
        while shape.cursor < len(shape.found):   # the landmark threats not yet looked at
            i = shape.found[shape.cursor]
            shape.cursor += 1
            if self._landmark(*self.entries[i][:2]):
                shape.hits.append(i)
                if counts(i):
                    return LANDMARK
        return PROMOTE

    def promote(self, g: str, out: dict[str, None]) -> None:
        """Add to ``out`` (in order, once each) the goals the needs ``g`` threatens are for;
        of a shape's threats, only those whose goal no conjunct before added can be new."""
        negs = self._negated(g)
        if negs:
            out.update((above, None) for _, _, above in self._all(g, negs) if above)
            return
        shape = self._shape(g)
        excused = self._excuses(g, shape)
        left = []
        for i in shape.pending:
            h, _, above = self.entries[i]
            if h != g and i not in excused:
                out.setdefault(above, None)
            else:
                left.append(i)
        shape.pending = left

    def _landmark(self, h: str, need: Literal) -> bool:
        k = self._keys.get(need)
        if k is None:
            k = self._keys[need] = key(need)
        return k in landmarks(self.task, self.goals[h])


class _Shape:
    """What achieving a conjunct of one shape threatens, before its own excuses: ``found``
    (entry indices, in order), ``by_above`` (those with a goal above, by its buckets) and
    ``above_lits``; ``hits`` (those to a landmark, found up to ``cursor``); ``pending``
    (those with a goal above that ``Threats.promote`` has not added yet)."""

    def __init__(self, found: list[int], entries: list):
        self.found = found
        self.above_lits = {i: literal(entries[i][2]) for i in found if entries[i][2]}
        self.by_above: dict[tuple, list[int]] = {}
        for i, lit in self.above_lits.items():
            for k in _buckets(lit):
                self.by_above.setdefault(k, []).append(i)
        self.hits: list[int] = []
        self.cursor = 0
        self.pending = [i for i in found if entries[i][2]]
