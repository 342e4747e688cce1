"""One thread's tick: run a body's step tree from its frames until one atomic step is issued,
the thread has to wait, or the body ends (seed 002, Appendix C).

Each construct checks its conditions before its running child, so the condition stack is
checked from the outermost down every cycle, that is after every atomic action (one per
cycle per thread). A ``:while``/``:until`` that fails deactivates the step where it is (it
continues from there when the condition holds again); a do-first whose first true condition
changed, or a do-best whose chosen alternative's condition failed, makes a new choice at
that level, dropping what ran below it. ``:when``/``:unless`` are checked once, before the
step starts. Instantaneous steps (model updates, subgoals that already hold, passed waits)
run on in the same cycle; a starred retry or a repeat round that would start again in the
cycle its last attempt started waits for the next cycle, so a cycle always ends.
"""

from __future__ import annotations

from dataclasses import replace

from ..core.arith import evaluate
from ..core.errors import EvalError
from ..core.matcher import ground
from ..core.program import Skill
from ..core.terms import Action, Literal, Var
from ..execution.paths import Found, PathFinder, Remembered, Walk
from ..reading.goals import satisfied
from .choosing import Choosing
from .results import OK, R, Res, added, env_with, fail, show_conds
from .state import Frame, ScsState, ThreadStatus, model_of
from .syntax import Act, Atomic, Construct, Kind, ModelUpdate, Subgoal, Wait, children

STEP_BUDGET = 256   # steps entered per thread and cycle before it yields [steps]


class Tick(Choosing):
    """Runs one thread for one cycle. Reads percepts and beliefs from ``walk``; writes the
    world model and do-best records straight into ``walk.updates["scs"]`` (so bodies nested
    through subgoals, run meanwhile, keep theirs); collects the actions issued
    (``actions``), the subgoal path that acts (``sub``) and what it did (``tally``)."""

    def __init__(self, finder: PathFinder, walk: Walk, skill: Skill, key: str, depth: int,
                 on_path: frozenset, prev_rest: Remembered):
        self.finder, self.walk, self.skill, self.key = finder, walk, skill, key
        self.depth, self.on_path, self.prev_rest = depth, on_path, prev_rest
        self.cycle = walk.state.cycle
        self.budget = STEP_BUDGET
        self.actions: list[Action] = []
        self.sub: Found | None = None
        self.draws = 0
        self.tally: dict[str, int] = {}

    # -- shared state ---------------------------------------------------------------------
    @property
    def scs(self) -> ScsState:
        return self.walk.current("scs")

    def put(self, scs: ScsState) -> None:
        self.walk.updates["scs"] = scs

    def bump(self, what: str, n: int = 1) -> None:
        """Count something done (added to the state's tally when the thread is stored)."""
        self.tally[what] = self.tally.get(what, 0) + n

    def holds(self, conds: tuple, env: dict) -> dict | None:
        """The first solution (in sorted order) of ``conds`` extending ``env``, or None."""
        if not conds:
            return env
        sols = self.finder.solutions(list(conds), env, self.walk)
        return sols[0] if sols else None

    def pick(self, options: list[int], at: tuple) -> int:
        """A nondeterministic choice, drawn from the agent's seeded generator."""
        if len(options) == 1:
            return options[0]
        self.draws += 1
        rng = self.walk.state.rng(f"scs/{self.key}/{'.'.join(map(str, at))}/{self.draws}")
        return rng.choice(options)

    # -- steps ----------------------------------------------------------------------------
    def run(self, node: object, frame: Frame | None, at: tuple, env: dict) -> Res:
        """Run ``node`` (at address ``at``) from ``frame`` (None: not started)."""
        self.budget -= 1
        if self.budget <= 0:
            return Res(R.IDLE, frame, f"more than {STEP_BUDGET} steps in one cycle: goes on "
                       "next cycle")
        if isinstance(node, Construct):
            return self.construct(node, frame, at, env)
        if isinstance(node, Act | Atomic):
            return self.atomic(node, frame, at, env)
        if isinstance(node, Subgoal):
            return self.subgoal(node, frame, at, env)
        if isinstance(node, ModelUpdate):
            return self.update(node, env)
        if isinstance(node, Wait):
            if self.holds(node.conds, env) is not None:
                return OK
            return Res(R.IDLE, frame or Frame(at), f"waits for {show_conds(node.conds, env)}")
        return fail(f"unknown step {node!r:.60}")

    def atomic(self, node: Act | Atomic, frame: Frame | None, at: tuple, env: dict) -> Res:
        """An atomic action or group: issue it; next cycle, succeed or fail by its outcome."""
        if frame is not None and frame.pending and frame.outcome == "running":
            # seed 002, Appendix C: an atomic action "is guaranteed to terminate within a
            # bounded time and cannot be interrupted": one whose outcome has not come yet is
            # still under way, and is sent again (the world continues a running operation)
            self.actions = [Action.from_list(a) for a in frame.pending]
            return Res(R.ACT, frame.but(outcome="", issued=self.cycle),
                       status=ThreadStatus.ACTING)
        if frame is not None and frame.pending:
            shown = " ".join(str(Action.from_list(a)) for a in frame.pending)
            if frame.outcome == "done":
                self.bump("actions done", len(frame.pending))
                return OK
            self.bump("actions failed")
            return fail(f"{shown} failed: {frame.reason or 'no outcome reported'}")
        steps = node.steps if isinstance(node, Atomic) else (node,)
        actions = []
        for s in steps:
            if isinstance(s, Act):
                try:
                    actions.append(Action(s.action.name, tuple(evaluate(x, env)
                                                               for x in s.action.args)))
                except EvalError as exc:
                    return fail(f"action cannot be evaluated: {exc}")
        clash = self.finder.conflict(self.walk, actions)
        if clash:
            return Res(R.IDLE, None, f"{' '.join(map(str, actions))} waits: {clash}")
        for s in steps:
            if isinstance(s, ModelUpdate):
                self.update(s, env)
        if not actions:
            return OK
        self.actions = actions
        return Res(R.ACT, Frame(at, pending=tuple(tuple(a.to_list()) for a in actions),
                                issued=self.cycle), status=ThreadStatus.ACTING)

    def subgoal(self, node: Subgoal, frame: Frame | None, at: tuple, env: dict) -> Res:
        """Achieve a concept through the skill hierarchy: success when it holds, failure when
        no executable path exists (a path blocked only by taken resources waits)."""
        goal = ground(node.literal, env)
        if satisfied(goal, self.walk.store):
            self.bump("subgoals achieved")
            return OK
        found = self.finder.achieve(self.walk, goal, self.prev_rest, self.depth + 1,
                                    self.on_path)
        frame = frame or Frame(at, since=self.cycle)
        if found is not None:
            self.sub = found
            if not found[1] and found[0] and found[0][-1].mode == "waiting":
                return Res(R.IDLE, frame, f"subgoal {goal} waits")
            return Res(R.ACT, frame, status=ThreadStatus.ACTING)
        if self._blocked_by_resources(goal):
            return Res(R.IDLE, frame, f"subgoal {goal} waits: its path's resources are taken")
        self.bump("subgoals failed")
        return fail(f"subgoal {goal} has no executable path")

    def _blocked_by_resources(self, goal: Literal) -> bool:
        """True when ``goal`` would have a path if no resource were taken this cycle."""
        w = self.walk
        if self.finder.res is None or not (w.taken or w.exclusive):
            return False
        scratch = Walk(w.program, w.pidx, w.store, w.state, w.outcomes, w.goal_id,
                       updates=dict(w.updates))
        return self.finder.achieve(scratch, goal, self.prev_rest, self.depth + 1,
                                   self.on_path) is not None

    def update(self, node: ModelUpdate, env: dict) -> Res:
        """assert/retract: change the world model (a belief from the next cycle on)."""
        fact = ground(node.fact, env)
        if any(isinstance(a, Var) for a in fact.args):
            return fail(f"{node}: fact {fact} has an unbound variable")
        row = (fact.pred, *fact.args)
        model = set(self.scs.model)
        if node.retract:
            model.discard(row)
        else:
            model.add(row)
        self.put(replace(self.scs, model=model_of(model)))
        self.bump("facts retracted" if node.retract else "facts asserted")
        return OK

    # -- constructs -----------------------------------------------------------------------
    def construct(self, node: Construct, frame: Frame | None, at: tuple, env: dict) -> Res:
        mods = node.mods
        if frame is None:
            frame = Frame(at)
            if mods.when is not None:
                sol = self.holds(mods.when, env)
                if sol is None:
                    return fail(f"({node.name} :when {show_conds(mods.when, env)}) is false")
                frame = frame.but(bind=added(sol, env))
            if mods.unless is not None and self.holds(mods.unless, env_with(env, frame.bind)) \
                    is not None:
                return fail(f"({node.name} :unless {show_conds(mods.unless, env)}) holds")
        inner = env_with(env, frame.bind)
        if mods.while_ is not None and self.holds(mods.while_, inner) is None:
            return Res(R.IDLE, frame, f"({node.name} :while {show_conds(mods.while_, inner)}) "
                       "is false: inactive", ThreadStatus.INACTIVE)
        if mods.until is not None and self.holds(mods.until, inner) is not None:
            return Res(R.IDLE, frame, f"({node.name} :until {show_conds(mods.until, inner)}) "
                       "holds: inactive", ThreadStatus.INACTIVE)
        run = {Kind.DO: self.seq, Kind.REPEAT: self.seq, Kind.ALL: self.all,
               Kind.ANY: self.any, Kind.FIRST: self.first, Kind.BEST: self.best}[node.kind]
        return run(node, frame, inner)
    def _child(self, node: Construct, frame: Frame, env: dict) -> Res:
        """Run the frame's current child; on ACT/IDLE return with the frame updated."""
        steps = children(node)
        r = self.run(steps[frame.cur], frame.child, (*frame.at, frame.cur),
                     env_with(env, frame.alt))
        if r.kind in (R.ACT, R.IDLE):
            return Res(r.kind, frame.but(child=r.frame), r.why, r.status)
        return r

    def _retry_later(self, frame: Frame, node: Construct, why: str) -> Res | None:
        """A starred retry waits for the next cycle when the failed attempt started in
        this one (it took no cycle, so retrying now would only fail again)."""
        if frame.since == self.cycle:
            return Res(R.IDLE, frame.but(child=None),
                       f"({node.name}) retries next cycle: {why}")
        return None

    def seq(self, node: Construct, frame: Frame, env: dict) -> Res:
        """do, do*, repeat, repeat*: the steps in order; do* and repeat* retry a failed step
        until it succeeds; repeat starts again after the last step."""
        n = len(node.steps)
        if frame.cur < 0:
            frame = frame.but(cur=0, since=self.cycle, began=self.cycle)
        while True:
            r = self._child(node, frame, env)
            if r.kind is not R.OK and r.kind is not R.FAIL:
                return r
            if r.kind is R.FAIL:
                if not node.star:
                    return fail(r.why)
                frame = frame.but(child=None, tries=frame.tries + 1)
                later = self._retry_later(frame, node, r.why)
                if later:
                    return later
                frame = frame.but(since=self.cycle)
                continue
            if frame.cur + 1 < n:
                frame = frame.but(cur=frame.cur + 1, child=None, since=self.cycle)
                continue
            if node.kind is not Kind.REPEAT:
                return OK
            quick = frame.began == self.cycle
            frame = frame.but(cur=0, child=None, rounds=frame.rounds + 1,
                            since=self.cycle, began=self.cycle)
            if quick:
                return Res(R.IDLE, frame, f"({node.name}) round {frame.rounds} took no "
                           "action: next round next cycle")

    def all(self, node: Construct, frame: Frame, env: dict) -> Res:
        """do-all: every step, in a nondeterministic order; fails as soon as one fails.
        do*-all retries failed steps, again in a nondeterministic order."""
        while True:
            if frame.cur < 0:
                left = [i for i in range(len(node.steps)) if i not in frame.done]
                if not left:
                    return OK
                frame = frame.but(cur=self.pick(left, frame.at), child=None,
                                since=self.cycle)
            r = self._child(node, frame, env)
            if r.kind is R.OK:
                frame = frame.but(done=tuple(sorted((*frame.done, frame.cur))), cur=-1,
                                child=None)
            elif r.kind is R.FAIL:
                if not node.star:
                    return fail(r.why)
                frame = frame.but(cur=-1, tries=frame.tries + 1)
                later = self._retry_later(frame, node, r.why)
                if later:
                    return later
            else:
                return r

    def any(self, node: Construct, frame: Frame, env: dict) -> Res:
        """do-any: one step chosen nondeterministically; on failure another not yet tried;
        fails when every one failed. do*-any chooses among all, failed ones included."""
        n = len(node.steps)
        while True:
            if frame.cur < 0:
                left = [i for i in range(n) if node.star or i not in frame.failed]
                if not left:
                    return fail(f"({node.name}) every alternative failed")
                frame = frame.but(cur=self.pick(left, frame.at), child=None,
                                since=self.cycle)
            r = self._child(node, frame, env)
            if r.kind is R.OK:
                return OK
            if r.kind is not R.FAIL:
                return r
            frame = frame.but(failed=tuple(sorted({*frame.failed, frame.cur})), cur=-1,
                            child=None, tries=frame.tries + 1)
            later = self._retry_later(frame, node, r.why) if node.star else None
            if later:
                return later
