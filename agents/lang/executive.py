"""The executive (seed 000, "Inference and Execution Mechanisms", "Adding Goal Priorities").

Each cycle it walks the prioritized goal list; the first unsatisfied goal gets a skill path: a
skill achieving the goal, then a skill for its first unsatisfied subgoal, down to a primitive
skill whose actions are the output. The goal's previous path is preferred: each remembered skill
is kept while its :requires hold (its :start is only checked on entry) and only the broken part
is replaced. With a (resources ...) section, lower goals may also act through free resources.
New skill kinds (SCS bodies, seed 002) plug in at ``_expand``; a problem solver at ``IMPASSE``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .arith import evaluate
from .errors import EvalError
from .explanation import Decision, GoalPath, GoalReport, GoalStatus, PassOver, PathStep
from .goals import GoalEntry, instances, ordered, satisfied
from .matcher import binding_key, first_failure, ground, solve, subst, unify_head
from .program import Program, Skill
from .state import EngineState, StoredStep
from .store import FactStore, PerceptIndex
from .terms import Action, Expr, Literal, PerceptPattern, Test, Var, fmt

MAX_DEPTH = 32       # deepest skill path [skills]
MAX_BINDINGS = 512   # alternative bindings considered per skill clause
MAX_WHY = 400        # explanation entries kept per cycle
_EVERY = " (for every match of the conditions before it)"


@dataclass
class _Ctx:
    pidx: PerceptIndex
    store: FactStore
    goal_id: str = ""
    taken: dict = field(default_factory=dict)   # resource -> goal id holding it
    exclusive: str = ""                           # goal id that took every resource
    why: list = field(default_factory=list)

    def passed(self, depth: int, goal: str, skill: str, b: dict, reason: str) -> None:
        if len(self.why) < MAX_WHY:
            self.why.append(PassOver(self.goal_id, depth, goal, skill, _btuple(b), reason))


class Executive:
    """Skill-path selection for one program; pure."""

    def __init__(self, program: Program):
        self.program = program
        self.res = program.resources

    def decide(self, state: EngineState, pidx: PerceptIndex, store: FactStore):
        """(Decision, next EngineState) for one cycle."""
        ctx = _Ctx(pidx, store)
        reports, paths = [], []
        remembered = dict(state.paths)
        stop = ""  # id of the goal in impasse that blocks the rest
        for e in ordered(state.goals):
            ctx.goal_id = e.id
            unsat = [i for i in instances(e.literal, self.program, pidx) if not satisfied(i, store)]
            prev = remembered.get(e.id, ())
            if not unsat:
                reports.append(GoalReport(e.id, e.text, e.priority, GoalStatus.SATISFIED))
                remembered.pop(e.id, None)
                continue
            waiting = GoalStatus.SUSPENDED if prev else GoalStatus.PENDING
            if stop or (paths and self.res is None) or ctx.exclusive:
                blocker = stop or ctx.exclusive or paths[0].goal_id
                reports.append(_report(e, waiting, unsat[0], f"waits: {blocker} comes first"))
                continue
            unsat.sort(key=lambda i: not prev or str(i) != prev[0].goal)
            found = None
            for inst in unsat:
                found = self._achieve(ctx, inst, prev if prev and prev[0].goal == str(inst)
                                      else (), 0, frozenset())
                if found:
                    break
            if found is None:
                if paths:
                    reports.append(_report(e, waiting, unsat[0], "no path with free resources"))
                else:
                    reports.append(_report(e, GoalStatus.IMPASSE, unsat[0],
                                           "no executable skill path"))
                    stop = e.id   # the first unsatisfied goal blocks lower ones (seed 000)
                continue
            steps, actions, stored = found
            used = self._take(ctx, e.id, actions)
            paths.append(GoalPath(e.id, tuple(steps), tuple(actions), used, bool(paths)))
            remembered[e.id] = tuple(stored)
            note = "acts in parallel through free resources" if len(paths) > 1 else ""
            reports.append(_report(e, GoalStatus.ACTIVE, inst, note))
        live = {e.id for e in state.goals}
        new_state = EngineState(state.goals, tuple(sorted((k, v) for k, v in remembered.items()
                                                          if k in live)),
                                state.next_seq, state.cycle + 1, state.extra)
        return Decision(state.cycle, tuple(reports), tuple(paths), tuple(ctx.why)), new_state

    # -- resources -------------------------------------------------------------------------
    def _resources(self, actions) -> frozenset[str] | None:
        """Resources the actions use; None when some action is undeclared (uses all)."""
        out: set[str] = set()
        for a in actions:
            r = self.res.get(a.name) if self.res is not None else None
            if r is None:
                return None
            out |= r
        return frozenset(out)

    def _conflict(self, ctx: _Ctx, actions) -> str:
        if self.res is None or not (ctx.taken or ctx.exclusive):
            return ""
        used = self._resources(actions)
        if used is None:
            return "resources taken: an undeclared action needs every resource"
        clash = sorted(used & set(ctx.taken))
        if clash:
            return "resources taken: " + ", ".join(f"{r} (by {ctx.taken[r]})" for r in clash)
        return ""

    def _take(self, ctx: _Ctx, goal_id: str, actions) -> tuple[str, ...]:
        used = self._resources(actions)
        if used is None:
            ctx.exclusive = goal_id
            return ("*all*",)
        for r in used:
            ctx.taken[r] = goal_id
        return tuple(sorted(used))

    # -- path finding ----------------------------------------------------------------------
    def _achieve(self, ctx: _Ctx, goal: Literal, prev: tuple, depth: int, on_path: frozenset):
        """(steps, actions, stored steps) of an executable path for ``goal``, or None."""
        text = str(goal)
        skills = self.program.skills_for(goal.pred)
        if not skills:
            ctx.passed(depth, text, "", {}, f"no skill achieves {goal.pred}")
            return None
        if depth >= MAX_DEPTH:
            ctx.passed(depth, text, "", {}, f"path deeper than {MAX_DEPTH} skills")
            return None
        if prev and prev[0].goal == text and prev[0].skill < len(self.program.skills):
            s = self.program.skills[prev[0].skill]
            if s.name == prev[0].skill_name:
                b = {Var(k): v for k, v in prev[0].bindings}
                found = self._continue(ctx, s, b, goal, prev[1:], depth, on_path)
                if found:
                    return found
        for n, s in enumerate(skills):
            found = self._enter(ctx, s, goal, depth, on_path)
            if found:
                for later in skills[n + 1:]:
                    ctx.passed(depth, text, later.name, {}, "not tried: an earlier skill applies")
                return found
        return None

    def _continue(self, ctx, s: Skill, prev_b: dict, goal: Literal, prev_rest, depth, on_path):
        """Keep the remembered skill: its head and :start bindings stay, percepts are matched
        afresh (their values change every cycle) and :requires must hold; :start is not checked."""
        text = str(goal)
        keep = set(s.head.variables())
        for c in s.start:
            if isinstance(c, Literal) and not c.negated:
                keep |= c.variables()
        b0 = unify_head(s.head, goal, {v: x for v, x in prev_b.items() if v in keep})
        if b0 is None:
            return None
        conds = [*s.percepts, *s.requires]
        sols = _solutions(conds, b0, ctx)
        if not sols:
            cond, b, several = first_failure(conds, b0, ctx.pidx, ctx.store)
            part = "percept not seen" if isinstance(cond, PerceptPattern) else "requires failed"
            ctx.passed(depth, text, s.name, b, f"previous skill no longer executable: {part}: "
                       f"{show(cond, b)}{_EVERY if several else ''}")
            return None
        for b in sols:
            found = self._expand(ctx, s, b, goal, prev_rest, depth, on_path, "continued")
            if found:
                return found
        return None

    def _enter(self, ctx, s: Skill, goal: Literal, depth: int, on_path):
        text = str(goal)
        b0 = unify_head(s.head, goal, {})
        if b0 is None:
            ctx.passed(depth, text, s.name, {}, f"head {s.head} does not match")
            return None
        conds = [*s.percepts, *s.start, *s.requires]
        sols = _solutions(conds, b0, ctx)
        if not sols:
            cond, b, several = first_failure(conds, b0, ctx.pidx, ctx.store)
            part = ("percept not seen" if isinstance(cond, PerceptPattern) else "start failed"
                    if any(cond is c for c in s.start) else "requires failed")
            ctx.passed(depth, text, s.name, b, f"{part}: {show(cond, b)}"
                       f"{_EVERY if several else ''}")
            return None
        for b in sols:
            found = self._expand(ctx, s, b, goal, (), depth, on_path, "entered")
            if found:
                return found
        return None

    def _expand(self, ctx, s: Skill, b: dict, goal: Literal, prev_rest, depth, on_path, mode):
        text = str(goal)
        key = (s.number, binding_key(b))
        if key in on_path:
            ctx.passed(depth, text, s.name, b, "already on the path with these bindings (loop)")
            return None
        step = PathStep(text, s.name, str(s.loc), _btuple(b), mode)
        stored = StoredStep(text, s.number, s.name, _btuple(b))
        if s.kind == "primitive":
            try:
                actions = [Action(a.name, tuple(evaluate(x, b) for x in a.args))
                           for a in s.actions]
            except EvalError as exc:
                ctx.passed(depth, text, s.name, b, f"action cannot be evaluated: {exc}")
                return None
            clash = self._conflict(ctx, actions)
            if clash:
                ctx.passed(depth, text, s.name, b, clash)
                return None
            return [step], actions, [stored]
        sub = next((g for g in (ground(x, b) for x in s.subgoals)
                    if not satisfied(g, ctx.store)), None)
        if sub is None:
            ctx.passed(depth, text, s.name, b, "every subgoal already holds (goal still false)")
            return None
        found = self._achieve(ctx, sub, prev_rest, depth + 1, on_path | {key})
        if found is None:
            ctx.passed(depth, text, s.name, b, f"subgoal {sub} has no executable path")
            return None
        steps, actions, st = found
        return [step, *steps], actions, [stored, *st]


def _solutions(conds: list, b0: dict, ctx: _Ctx) -> list[dict]:
    """Distinct solutions of ``conds`` extending ``b0``, in a deterministic order (capped)."""
    sols: dict = {}
    for b in solve(conds, b0, ctx.pidx, ctx.store):
        sols.setdefault(binding_key(b), b)
        if len(sols) >= MAX_BINDINGS:
            break
    return [sols[k] for k in sorted(sols)]


def _btuple(b: dict) -> tuple:
    return tuple(sorted(((v.name, x) for v, x in b.items() if not isinstance(x, Var)),
                        key=lambda kv: kv[0]))


def _report(e: GoalEntry, status: GoalStatus, inst: Literal, note: str = "") -> GoalReport:
    bindings = tuple((g.name, a) for g, a in zip(e.literal.args, inst.args, strict=True)
                     if isinstance(g, Var) and not isinstance(a, Var))
    return GoalReport(e.id, e.text, e.priority, status, bindings, str(inst), note)


def show(cond: object, b: dict) -> str:
    """A condition with its bound variables replaced by values, for explanations."""
    if isinstance(cond, Literal):
        return str(ground(cond, b))
    if isinstance(cond, PerceptPattern):
        return str(PerceptPattern(cond.type, subst(cond.id, b),
                                  tuple((a, subst(t, b)) for a, t in cond.attrs)))
    if isinstance(cond, Test):
        return _show_expr(cond.expr, b)
    return fmt(cond)


def _show_expr(e: object, b: dict) -> str:
    if isinstance(e, Expr):
        return "(" + " ".join([e.op, *(_show_expr(a, b) for a in e.args)]) + ")"
    return fmt(subst(e, b))
