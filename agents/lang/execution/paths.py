"""How a skill path is chosen (seed 000, "Inference and Execution Mechanisms").

A skill path starts with a skill that achieves the goal; a nonprimitive skill's next element
achieves its first unsatisfied subgoal, down to a primitive skill whose actions are the
output. A path is executable when the start conditions of every skill on it hold. The
previous cycle's path is preferred: each remembered skill is kept while its :requires hold
(its :start is checked only on entry, or again when its goal resumes after a suspension) and
only the broken part is replaced.

The walk is owned here (as py_trees' tick); each kind of skill body answers through one
interface, ``BodyRunner.expand``: primitive skills give actions, subgoal skills recurse on
their first unsatisfied subgoal, and further kinds (SCS bodies, seed 002) register in
``agents.lang.execution.bodies``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from itertools import chain
from typing import Any, Protocol

from ..core.explanation import PassOver, PathStep
from ..core.matcher import binding_key, first_failure, ground, solve, subst, unify_head
from ..core.outcomes import Outcome
from ..core.program import Program, Skill
from ..core.store import FactStore, PerceptIndex
from ..core.terms import Action, Expr, Literal, PerceptPattern, Test, Var, fmt
from .effects import Effects, undoing
from .state import EngineState, StoredStep

MAX_DEPTH = 64       # deepest skill path [skills] (a learned skill recurses twice per block
                     # of a tower: 30 blocks need 60)
MAX_BINDINGS = 512   # alternative bindings considered per skill clause
MAX_WHY = 400        # explanation entries kept per cycle
_EVERY = " (for every match of the conditions before it)"

Found = tuple[list[PathStep], list[Action], list[StoredStep]]
"""An executable path: its steps (for the explanation), its actions, what to remember."""


@dataclass(frozen=True, slots=True)
class Remembered:
    """The part of a goal's previous path still to be matched, top first. ``resume``: the
    goal is coming back from a suspension, so every :start on it is checked again."""

    steps: tuple[StoredStep, ...] = ()
    resume: bool = False

    def rest(self) -> Remembered:
        """What remains below the first step."""
        return Remembered(self.steps[1:], self.resume)


NOTHING = Remembered()


@dataclass
class Walk:
    """One cycle's walk over the goal list: what path finding, every body kind and every
    mechanism read (percepts, beliefs, last cycle's outcomes, the state at the start of the
    cycle) and write (resources taken, explanations, mechanism state for the next cycle)."""

    program: Program
    pidx: PerceptIndex
    store: FactStore
    state: EngineState
    outcomes: tuple[Outcome, ...] = ()
    goal_id: str = ""
    taken: dict = field(default_factory=dict)   # resource -> goal id holding it
    exclusive: str = ""                           # goal id that took every resource
    why: list = field(default_factory=list)
    sections: list = field(default_factory=list)  # Section values for the Decision
    updates: dict[str, Any] = field(default_factory=dict)  # EngineState field -> new value
    protected: list = field(default_factory=list)  # (goal id, text, ground literals) of the
    #                                                satisfied goals before the current one
    banned: frozenset = frozenset()  # (goal text, skill number, bindings) not to be used for
    #                                  the current goal (agents/lang/execution/loops.py)

    def passed(self, depth: int, goal: str, skill: str, b: dict, reason: str) -> None:
        """Record why a skill (or goal) was passed over."""
        if len(self.why) < MAX_WHY:
            self.why.append(PassOver(self.goal_id, depth, goal, skill, btuple(b), reason))

    def current(self, name: str) -> Any:
        """The value of EngineState field ``name`` as updated so far this cycle."""
        return self.updates.get(name, getattr(self.state, name))


class BodyRunner(Protocol):
    """One kind of skill body: given an entered (or continued) skill with its bindings,
    answer with an executable path below it or None (recording why in ``walk``)."""

    def expand(self, finder: PathFinder, walk: Walk, skill: Skill, b: dict, goal: Literal,
               prev_rest: Remembered, depth: int, on_path: frozenset, step: PathStep,
               stored: StoredStep) -> Found | None: ...


class PathFinder:
    """Skill-path search over one program; pure. ``bodies`` maps ``Skill.kind`` to its runner."""

    def __init__(self, program: Program, bodies: dict[str, BodyRunner]):
        self.program = program
        self.res = program.resources
        self.bodies = bodies
        self.effects = Effects(program)
        # by skill number: the variables a continued skill keeps, by name (the skill's own
        # Var objects, so that its bindings are found by identity)
        self.kept = [{v.name: v for v in _kept_vars(s)} for s in program.skills]

    # -- higher goals ------------------------------------------------------------------------
    def undoes(self, walk: Walk, actions) -> str:
        """Why ``actions`` may not run for the current goal ("" if they may): the program says
        they undo a literal by which a more important goal holds
        (agents/lang/execution/effects.py)."""
        return undoing(self.effects, walk.protected, actions)

    # -- resources -------------------------------------------------------------------------
    def resources(self, actions) -> frozenset[str] | None:
        """Resources the actions use; None when some action is undeclared (uses all)."""
        out: set[str] = set()
        for a in actions:
            r = self.res.get(a.name) if self.res is not None else None
            if r is None:
                return None
            out |= r
        return frozenset(out)

    def conflict(self, walk: Walk, actions) -> str:
        """Why ``actions`` cannot run this cycle ("" if their resources are free)."""
        if self.res is None or not (walk.taken or walk.exclusive):
            return ""
        used = self.resources(actions)
        if used is None:
            return "resources taken: an undeclared action needs every resource"
        clash = sorted(used & set(walk.taken))
        if clash:
            return "resources taken: " + ", ".join(f"{r} (by {walk.taken[r]})" for r in clash)
        return ""

    def take(self, walk: Walk, goal_id: str, actions) -> tuple[str, ...]:
        """Mark the resources ``actions`` use as held by ``goal_id``."""
        used = self.resources(actions)
        if used is None:
            walk.exclusive = goal_id
            return ("*all*",)
        for r in used:
            walk.taken[r] = goal_id
        return tuple(sorted(used))

    # -- path finding ----------------------------------------------------------------------
    def achieve(self, walk: Walk, goal: Literal, prev: Remembered, depth: int,
                on_path: frozenset) -> Found | None:
        """An executable path for ``goal``, preferring the remembered one ``prev``."""
        text = str(goal)
        skills = self.program.skills_for(goal.pred)
        if not skills:
            walk.passed(depth, text, "", {}, f"no skill achieves {goal.pred}")
            return None
        if depth >= MAX_DEPTH:
            walk.passed(depth, text, "", {}, f"path deeper than {MAX_DEPTH} skills")
            return None
        s = self.remembered(prev, text)
        if s is not None:
            found = self.keep(walk, s, prev.steps[0].bindings, goal, text, prev, depth,
                              on_path)
            if found:
                return found
        for n, s in enumerate(skills):
            found = self.enter(walk, s, goal, text, depth, on_path)
            if found:
                for later in skills[n + 1:]:
                    walk.passed(depth, text, later.name, {}, "not tried: an earlier skill applies")
                return found
        return None

    def remembered(self, prev: Remembered, text: str) -> Skill | None:
        """The skill remembered at the head of ``prev`` for goal ``text``, if the program
        still has it (a changed program's stale path is ignored)."""
        if not prev.steps:
            return None
        head = prev.steps[0]
        if head.goal != text or head.skill >= len(self.program.skills):
            return None
        s = self.program.skills[head.skill]
        return s if s.name == head.skill_name else None

    def keep(self, walk: Walk, s: Skill, bindings: tuple, goal: Literal, text: str,
             prev: Remembered, depth, on_path) -> Found | None:
        """Keep the remembered skill: its head and :start bindings stay, percepts are matched
        afresh (their values change every cycle) and :requires must hold; :start is checked
        only when resuming after a suspension."""
        keep = self.kept[s.number]  # (s is one of the program's skills: ``remembered``)
        b0 = unify_head(s.head, goal, {keep[k]: x for k, x in bindings if k in keep})
        if b0 is None:
            return None
        resume = prev.resume
        conds = [*s.percepts, *s.requires, *(s.start if resume else ())]
        sols = self.solutions(conds, b0, walk)
        if not sols:
            cond, b, several = first_failure(conds, b0, walk.pidx, walk.store)
            part = ("percept not seen" if isinstance(cond, PerceptPattern) else "start failed"
                    if any(cond is c for c in s.start) else "requires failed")
            lead = "cannot resume the previous skill" if resume else \
                "previous skill no longer executable"
            walk.passed(depth, text, s.name, b, f"{lead}: {part}: {show(cond, b)}"
                        f"{_EVERY if several else ''}")
            return None
        for b in sols:
            found = self.expand(walk, s, b, goal, text, prev.rest(), depth, on_path,
                                "resumed" if resume else "continued")
            if found:
                return found
        return None

    def enter(self, walk: Walk, s: Skill, goal: Literal, text: str, depth: int,
              on_path) -> Found | None:
        """Enter skill ``s`` afresh for ``goal`` (``text``: the goal as text): percepts, :start
        and :requires must hold."""
        b0 = unify_head(s.head, goal, {})
        if b0 is None:
            walk.passed(depth, text, s.name, {}, f"head {s.head} does not match")
            return None
        conds = [*s.percepts, *s.start, *s.requires]
        sols = self.solutions(conds, b0, walk)
        if not sols:
            cond, b, several = first_failure(conds, b0, walk.pidx, walk.store)
            part = ("percept not seen" if isinstance(cond, PerceptPattern) else "start failed"
                    if any(cond is c for c in s.start) else "requires failed")
            walk.passed(depth, text, s.name, b, f"{part}: {show(cond, b)}"
                        f"{_EVERY if several else ''}")
            return None
        for b in sols:
            if walk.banned and (text, s.number, btuple(b)) in walk.banned:
                walk.passed(depth, text, s.name, b, "not used again for this goal: it led "
                            "back to an earlier situation (loop)")
                continue
            found = self.expand(walk, s, b, goal, text, NOTHING, depth, on_path, "entered")
            if found:
                return found
        return None

    def expand(self, walk: Walk, s: Skill, b: dict, goal: Literal, text: str,
               prev_rest: Remembered, depth: int, on_path: frozenset,
               mode: str) -> Found | None:
        """The path below skill ``s`` (bound by ``b``), through its body kind's runner."""
        key = (s.number, binding_key(b))
        if key in on_path:
            walk.passed(depth, text, s.name, b, "already on the path with these bindings (loop)")
            return None
        bound = btuple(b)
        step = PathStep(text, s.name, str(s.loc), bound, mode)
        stored = StoredStep(text, s.number, s.name, bound)
        return self.bodies[s.kind].expand(self, walk, s, b, goal, prev_rest, depth,
                                          on_path | {key}, step, stored)

    def solutions(self, conds: list, b0: dict, walk: Walk) -> list[dict]:
        """Distinct solutions of ``conds`` extending ``b0``, in a deterministic order."""
        found = solve(conds, b0, walk.pidx, walk.store)
        first = next(found, None)
        if first is None:
            return []
        second = next(found, None)
        if second is None:   # the usual case: one solution, nothing to order
            return [first]
        sols: dict = {binding_key(first): first}
        for b in chain((second,), found):
            sols.setdefault(binding_key(b), b)
            if len(sols) >= MAX_BINDINGS:
                break
        return [sols[k] for k in sorted(sols)]


def _kept_vars(s: Skill) -> frozenset[Var]:
    """The variables a continued skill keeps from last cycle: its head's and those its
    positive :start literals bind."""
    keep = set(s.head.variables())
    for c in s.start:
        if isinstance(c, Literal) and not c.negated:
            keep |= c.variables()
    return frozenset(keep)


def btuple(b: dict) -> tuple:
    """Bindings as sorted ((name, value), ...), leaving out unbound variables."""
    return tuple(sorted(((v.name, x) for v, x in b.items() if not isinstance(x, Var)),
                        key=lambda kv: kv[0]))


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
