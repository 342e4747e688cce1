"""Ways the means-ends solver leaves out (issue 22), a part of Task (agents/lang/solving/
task.py): a skill whose actions would undo a protected goal, a higher one that holds (seed 000,
"Adding Goal Priorities"), and a way whose own condition can only be reached through the goal
it is for (a landmark of the condition; agents/lang/solving/landmarks.py)."""

from __future__ import annotations

from ..core.arith import evaluate
from ..core.errors import EvalError
from ..core.matcher import ground as ground_literal
from ..core.matcher import unify_head
from ..core.program import Skill
from ..core.terms import Action, Literal
from ..execution.effects import undone_goal
from .landmarks import key, landmarks


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
