"""Choosing constructs (seed 002, Appendix C): do-first, whose pairs' conditions are rechecked
every cycle as in a T-R program, and do-best, which picks by utility times the alternative's
learned discount factor (section 3, "Best-First Behavior"; Appendix A, "Learning"). A mixin of
``Tick`` (agents/lang/scs/constructs.py), whose helpers it uses."""

from __future__ import annotations

from dataclasses import replace

from ..core.arith import evaluate
from ..core.errors import EvalError
from ..core.terms import Var
from .learning import record, reward_value
from .results import OK, R, Res, added, env_with, fail
from .state import Choice, Frame, ThreadStatus
from .syntax import Branch, Construct, uses


class Choosing:
    """do-first and do-best, and how a chosen alternative is kept or abandoned."""

    def still(self, br: Branch, frame: Frame, env: dict) -> dict | None:
        """Whether the chosen alternative's condition still holds: with the values of the
        variables its step reads kept, the others matched afresh (a distance that changes
        every cycle does not make it fail); the solution, or None."""
        used = uses(br.step)
        kept = tuple((k, v) for k, v in frame.alt if Var(k) in used)
        return self.holds(br.conds, env_with(env, kept))

    def finished(self, node: Construct, frame: Frame, env: dict) -> Res | None:
        """Whether the running alternative has just ended (its last action's outcome or its
        subgoal's achievement arrived this cycle): its result, or None when it would go on,
        leaving no trace of having looked. An alternative whose condition no longer holds
        is abandoned only if it has not ended: the finished action's result comes first."""
        if frame.cur < 0 or frame.child is None:
            return None
        w = self.walk
        saved = (dict(w.updates), len(w.why), self.actions, self.sub, self.budget, self.draws,
                 dict(self.tally))
        r = self._child(node, frame, env)
        if r.kind in (R.OK, R.FAIL):
            return r
        w.updates.clear()
        w.updates.update(saved[0])
        del w.why[saved[1]:]
        self.actions, self.sub, self.budget, self.draws, self.tally = saved[2:]
        return None

    def first(self, node: Construct, frame: Frame, env: dict) -> Res:
        """do-first: the step of the first pair whose condition holds, the conditions
        rechecked every cycle as in a T-R program (seed 002, Appendix B); fails when that
        step fails. do*-first tries again (after a fresh scan) instead."""
        while True:
            j, sol, same = -1, None, False
            for i, br in enumerate(node.steps):
                if i == frame.cur:
                    sol = self.still(br, frame, env)
                    same = sol is not None
                sol = sol if same else self.holds(br.conds, env)
                if sol is not None:
                    j = i
                    break
            r = None if same else self.finished(node, frame, env)
            if r is None:
                if j < 0:
                    return Res(R.IDLE, frame, f"({node.name}) no condition holds: inactive",
                               ThreadStatus.INACTIVE)
                frame = frame.but(alt=added(sol, env)) if same else \
                    frame.but(cur=j, alt=added(sol, env), child=None, since=self.cycle)
                r = self._child(node, frame, env)
            if r.kind is R.OK:
                return OK
            if r.kind is not R.FAIL:
                return r
            if not node.star:
                return fail(r.why)
            frame = frame.but(cur=-1, alt=(), child=None, tries=frame.tries + 1)
            later = self._retry_later(frame, node, r.why)
            if later:
                return later

    def best(self, node: Construct, frame: Frame, env: dict) -> Res:
        """do-best: among the alternatives whose condition holds, the highest utility times
        discount factor; ties by do-any rules; failures as do-any (do*-best: as do*-any)."""
        while True:
            r = None
            if frame.cur >= 0:
                sol = self.still(node.steps[frame.cur], frame, env)
                if sol is not None:
                    frame = frame.but(alt=added(sol, env))
                else:
                    r = self.finished(node, frame, env)
                    if r is None:
                        frame = frame.but(cur=-1, alt=(), child=None)   # abandoned
            if r is None:
                if frame.cur < 0:
                    chosen = self._bid(node, frame, env)
                    if isinstance(chosen, Res):
                        return chosen
                    frame = chosen
                r = self._child(node, frame, env)
            if r.kind is not R.OK and r.kind is not R.FAIL:
                return r
            self._learn(node, frame, env, r.kind is R.OK)
            if r.kind is R.OK:
                return OK
            frame = frame.but(failed=tuple(sorted({*frame.failed, frame.cur})), cur=-1,
                            alt=(), child=None, tries=frame.tries + 1)
            later = self._retry_later(frame, node, r.why) if node.star else None
            if later:
                return later

    def _bid(self, node: Construct, frame: Frame, env: dict) -> Frame | Res:
        """Choose the alternative with the highest discounted utility (seed 002, section 3,
        "Best-First Behavior"; Appendix A, "Learning")."""
        bids = []
        for i, br in enumerate(node.steps):
            if not node.star and i in frame.failed:
                continue
            sol = self.holds(br.conds, env)
            if sol is None:
                continue
            try:
                u = evaluate(br.utility, sol)
            except EvalError:
                continue
            if isinstance(u, bool) or not isinstance(u, int | float):
                continue
            bids.append((u * self.choice(node, frame.at, i).factor, i, sol))
        if not bids:
            if len(frame.failed) == len(node.steps) and not node.star:
                return fail(f"({node.name}) every alternative failed")
            if frame.failed and not node.star:
                # seed 002, Appendix C: do-best's failure semantics are do-any's; after a
                # failure the next true alternative is tried, and with none left the do-best
                # fails in the same decision (it does not wait, inactive, for a condition)
                tried = ", ".join(str(node.steps[i].step) for i in frame.failed)
                return fail(f"({node.name}) {tried} failed and no other alternative's "
                            "condition holds")
            return Res(R.IDLE, frame, f"({node.name}) no alternative's condition holds: "
                       "inactive", ThreadStatus.INACTIVE)
        top = max(b[0] for b in bids)
        i = self.pick([b[1] for b in bids if b[0] == top], frame.at)
        sol = next(b[2] for b in bids if b[1] == i)
        c = self.choice(node, frame.at, i)
        self.set_choice(replace(c, chosen=c.chosen + 1))
        return frame.but(cur=i, alt=added(sol, env), child=None, since=self.cycle)

    def choice(self, node: Construct, at: tuple, i: int) -> Choice:
        key = f"{self.skill.name}@{'.'.join(map(str, (*at, i)))}"
        found = self.scs.choice(key)
        if found is not None:
            return found
        br = node.steps[i]
        when = f" when {' '.join(str(c) for c in br.conds)}" if br.conds else ""
        return Choice(key, f"{br.step}{when} ({br.loc})")

    def set_choice(self, c: Choice) -> None:
        rest = [x for x in self.scs.choices if x.key != c.key]
        self.put(replace(self.scs, choices=tuple(sorted([*rest, c], key=lambda x: x.key))))

    def _learn(self, node: Construct, frame: Frame, env: dict, ok: bool) -> None:
        """Reinforce the chosen alternative's discount factor by the measured result."""
        br = node.steps[frame.cur]
        result = 1.0
        if ok and br.reward is not None:
            try:
                result = reward_value(evaluate(br.reward, env_with(env, frame.alt)))
            except EvalError:
                result = 0.0
        self.set_choice(record(self.choice(node, frame.at, frame.cur), ok, result))
