"""How the means-ends solver ranks the bindings of a way to chain off (a part of Task,
agents/lang/solving/task.py): the most conditions holding, after the relaxed estimate
(agents/lang/solving/relaxed.py) where the program admits one; a single binding is not ranked."""

from __future__ import annotations

from ..core.matcher import unify_head
from ..core.terms import Literal
from ..execution.paths import show
from .relaxed import Relaxed

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
