"""Which conjuncts of a conjunction threaten which needs of the others' plans
(agents/lang/solving/ordering.py, ``agenda``), without comparing every pair.

``threatens(task, g, need, above)`` is the definition: achieving the conjunct g makes the
need false (it is an instance of a pattern g undoes, ``task.effects.undoes``), unless g also
achieves ``above``, the goal the need is needed for; a negated need is threatened when g is
an instance of its positive core. Compared pair by pair, a conjunction of n literals whose
plans need k literals each costs n * n * k checks (visitall's 144 cells: 285,000 a cycle).

``Threats`` gives the same answers by indexing: the needs of all plans by predicate and by
their first constant argument, so that a pattern is compared only with the needs it can
cover; and the conjuncts by what achieving them undoes (their *shape*: every cell of
visitall undoes ``(at-robot ?from)``), so that the needs a shape threatens are found once for
all conjuncts of that shape. What each conjunct achieves with it excuses a few of those (the
needs for ``(at-robot X)``, which visiting X achieves), found through an index of the shape's
threats by the goal they are needed for; its own plan is left out by position; a negated
need, which depends on the conjunct itself, is checked per conjunct among the needs of its
predicate. What the agenda asks (is there a threat, is one to a landmark, which goals are
the threatened needs for) is answered from the shape's list without copying it per conjunct.
Pure; one per agenda."""

from __future__ import annotations

from ..core.terms import Literal, Var
from ..execution.effects import undone_by
from .landmarks import key, landmarks
from .state import literal

FREE, LANDMARK, PROMOTE = "free", "landmark", "promote"


def threatens(task, g: str, need: Literal, above: str = "") -> bool:
    """True when achieving the conjunct ``g`` makes ``need`` false, unless it also achieves
    ``above``, the goal ``need`` is needed for (a program stating its skills' effects:
    stacking B, held to be put down to clear it, on A clears it as well)."""
    lit = literal(g)
    if need.negated:
        return undone_by(lit, (Literal(need.pred, need.args),))
    if need.variables() or not undone_by(need, task.effects.undoes(lit)):
        return False
    return not (above and undone_by(literal(above), tuple(task.effects.achieved_with(lit))))


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
