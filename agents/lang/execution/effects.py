"""What an action is known to achieve and to undo, read from the program alone (the
solver "does not undo a goal of higher priority that holds"; seed 000, "Adding Goal
Priorities": higher goals "always hold during execution of low-priority tasks").

A program says what an action achieves through the heads of the primitive skill clauses that
perform it (seed 000 writes an action with two effects as one clause per effect: in
programs/blocks.tlp ``(*unstack ?c ?b)`` achieves ``(clear ?b)`` and ``(holding ?c)``). What
achieving a literal E undoes follows from the concept definitions:

* E's own definition: when every clause of E's concept requires ``(not Q)``, achieving E makes
  every instance of Q false (``(clear B)`` excludes ``(on ?any B)``);
* the definitions that exclude E: a concept each of whose clauses requires ``(not E')``, E'
  matching E, becomes false (``(holding C)`` undoes ``(clear C)``; ``(on B C)`` undoes
  ``(clear C)``);
* then, twice more, a concept each of whose clauses needs, positively, something undone
  (``(unstackable C B)`` needs ``(on C B)``).

A primitive skill may also state its actions' effects, ``:effects ((clear ?x) (not (holding
?x)))`` (the pddl world's programs: world/pddl/program.py): its positive effects are achieved
with its head, its ``(not L)`` undone; and achieving E undoes what every primitive skill with
E's predicate in its head and stated effects deletes (``(on A B)``, which only *stack achieves,
undoes ``(clear B)``; ``(holding A)``, by *pick-up or *unstack, undoes ``(clear A)``).

Only fully known effects count: a clause whose action arguments are expressions, or whose head
keeps a variable the action does not bind, says nothing. So the prediction never claims too
much; an effect the program does not state (``(*pickup A T)`` empties the table spot, fills the
hand) is not predicted, and the executive's switching back to a violated higher goal and the
loop watch (agents/lang/execution/loops.py) handle it. Pure; cached per program."""

from __future__ import annotations

from ..core.program import ConceptClause, Program
from ..core.terms import Action, Expr, Literal, Var

CLOSURE = 2   # rounds of "needs something undone" [rounds]
_MAX_CACHE = 4096


class Effects:
    """The effect model of one program (see the module docstring)."""

    def __init__(self, program: Program):
        self.program = program
        self._actions: dict[tuple, tuple[tuple[Literal, ...], tuple[Literal, ...]]] = {}
        self._undoes: dict[Literal, tuple[Literal, ...]] = {}
        self._achieved: dict[Literal, tuple[Literal, ...]] = {}
        # primitive skills with :actions by the names and arities of their actions, in
        # program order: the only ones ``_action_binding`` can bind for actions of that shape
        # (actions with continuous values are new every cycle, so the cache below misses)
        self._performing: dict[tuple, list] = {}
        for s in program.skills:
            if s.kind == "primitive" and s.actions:
                self._performing.setdefault(_shape(s.actions), []).append(s)

    # -- actions -----------------------------------------------------------------------------
    def of_actions(self, actions: tuple[Action, ...] | list[Action]
                   ) -> tuple[tuple[Literal, ...], tuple[Literal, ...]]:
        """(achieved literals, undone patterns) of executing ``actions`` in one cycle;
        variables in a pattern stand for any value."""
        key = tuple((a.name, a.args) for a in actions)
        hit = self._actions.get(key)
        if hit is None:
            stated = [(s, b) for s in self._performing.get(_shape(actions), ())
                      for b in [_action_binding(s, actions)] if b is not None]
            heads = [_pattern(s.head, b) for s, b in stated]
            adds = [_pattern(e, b) for s, b in stated for e in s.effects if not e.negated]
            achieved = tuple(dict.fromkeys(h for h in heads + adds if not h.variables()))
            deletes = [_pattern(e, b) for s, b in stated for e in s.effects if e.negated]
            undone = tuple(dict.fromkeys([*(d for d in deletes if not d.variables()),
                                          *(p for e in achieved for p in self.undoes(e))]))
            undone = tuple(p for p in undone if not any(_covers(p, e) for e in achieved))
            hit = (achieved, undone)
            if len(self._actions) < _MAX_CACHE:
                self._actions[key] = hit
        return hit

    # -- literals ----------------------------------------------------------------------------
    def undoes(self, e: Literal) -> tuple[Literal, ...]:
        """Patterns of what achieving the ground literal ``e`` makes false."""
        hit = self._undoes.get(e)
        if hit is not None:
            return hit
        out = list(self._excluded_by(e)) + list(self._excluding(e)) + self._deleted_with(e)
        frontier = list(out)
        for _ in range(CLOSURE):
            frontier = [p for q in frontier for p in self._needing(q) if p not in out]
            out += frontier
        hit = tuple(dict.fromkeys(out))
        if len(self._undoes) < _MAX_CACHE:
            self._undoes[e] = hit
        return hit

    def _deleted_with(self, e: Literal) -> list[Literal]:
        """What every primitive skill that states its effects and can achieve ``e`` deletes
        (its head or a positive effect matching ``e``); variables ``e`` leaves open stand for
        any value."""
        return self._stated_with(e, True)

    def achieved_with(self, e: Literal) -> tuple[Literal, ...]:
        """What every primitive skill that states its effects and can achieve ``e`` also
        achieves (``(on A B)`` by *stack comes with ``(clear A)``), as patterns; kept as
        ``undoes`` keeps its answers."""
        hit = self._achieved.get(e)
        if hit is None:
            hit = tuple(p for p in self._stated_with(e, False) if p != _canonical(e))
            if len(self._achieved) < _MAX_CACHE:
                self._achieved[e] = hit
        return hit

    def _stated_with(self, e: Literal, negated: bool) -> list[Literal]:
        common: list[Literal] | None = None
        for s in self.program.skills:
            if s.kind != "primitive" or not s.effects:
                continue
            for made in (s.head, *(x for x in s.effects if not x.negated)):
                b = _bind(Literal(made.pred, made.args), e)
                if b is None or not self._admits(s, b):
                    continue
                found = {_canonical(_pattern(x, b)) for x in (s.head, *s.effects)
                         if x.negated == negated}
                common = sorted(found, key=str) if common is None else \
                    [x for x in common if x in found]
        return common or []

    def _admits(self, s, b: dict) -> bool:
        """Whether skill ``s`` can take the objects ``b`` binds (every skill here; the
        solver's typed model narrows it, agents/lang/solving/typed.py)."""
        return True

    def _clauses(self, pred: str) -> tuple[ConceptClause, ...]:
        return self.program.concepts.get(pred, ())

    def _excluded_by(self, e: Literal) -> list[Literal]:
        """What ``e``'s own definition excludes: (not Q) in its single defining clause."""
        clauses = self._clauses(e.pred)
        if len(clauses) != 1:
            return []
        b = _bind(clauses[0].head, e)
        if b is None:
            return []
        return [_pattern(r, b) for r in clauses[0].relations if r.negated]

    def _excluding(self, e: Literal) -> list[Literal]:
        """Concepts every clause of which requires ``(not E')`` with E' matching ``e``."""
        out = []
        for clauses in self.program.concepts.values():
            heads = []
            for c in clauses:
                found = None
                for r in c.relations:
                    if r.negated and r.pred == e.pred:
                        b = _bind(Literal(r.pred, r.args), e)
                        if b is not None:
                            found = _pattern(c.head, b)
                            break
                if found is None:
                    break
                heads.append(found)
            else:
                if len(heads) == 1:
                    out.append(heads[0])
        return out

    def _needing(self, p: Literal) -> list[Literal]:
        """Concepts whose single clause needs, positively, every instance it could use of the
        undone pattern ``p`` (its own variables outside the head left open by ``p``)."""
        out = []
        for clauses in self.program.concepts.values():
            if len(clauses) != 1:
                continue
            c = clauses[0]
            head_vars = c.head.variables()
            for r in c.relations:
                if r.negated or r.pred != p.pred or len(r.args) != len(p.args):
                    continue
                b: dict = {}
                ok = True
                for ra, pa in zip(r.args, p.args, strict=True):
                    if isinstance(ra, Var) and ra not in head_vars:
                        ok = ok and isinstance(pa, Var)   # existential: p must cover all
                    elif isinstance(ra, Var):
                        if not isinstance(pa, Var):
                            ok = ok and b.setdefault(ra, pa) == pa
                    elif not isinstance(pa, Var) and pa != ra:
                        ok = False
                if ok:
                    out.append(_pattern(c.head, b))
                    break
        return out


def undoing(effects: Effects, protected: tuple | list, actions) -> str:
    """Why ``actions`` may not be taken ("" if they may): the program says they undo a
    literal by which a protected goal holds (``undone_goal``)."""
    hit = undone_goal(effects, protected, actions)
    return "" if hit is None else \
        f"would undo {hit[2]} of goal {hit[0]} {hit[1]}, which holds and comes first"


def undone_goal(effects: Effects, protected: tuple | list, actions
                ) -> tuple[str, str, Literal] | None:
    """(goal id, goal text, literal) of the first protected goal ``actions`` would undo, or
    None. ``protected``: (goal id, text, ground literals) of the goals that hold and come
    first; a negated literal is undone by achieving its core."""
    if not protected or not actions:
        return None
    achieved, undone = effects.of_actions(actions)
    for gid, text, lits in protected:
        for lit in lits:
            core = Literal(lit.pred, lit.args)
            if undone_by(core, achieved if lit.negated else undone):
                return gid, text, lit
    return None


def undone_by(lit: Literal, patterns: tuple[Literal, ...]) -> bool:
    """True when the ground literal ``lit`` (negated: its positive core must not become
    true, judged by ``achieved`` patterns instead) matches one of ``patterns``."""
    return any(_covers(p, lit) for p in patterns)


def _covers(pattern: Literal, lit: Literal) -> bool:
    if pattern.pred != lit.pred or len(pattern.args) != len(lit.args):
        return False
    b: dict = {}
    for pa, la in zip(pattern.args, lit.args, strict=True):
        if isinstance(pa, Var):
            if b.setdefault(pa, la) != la:
                return False
        elif isinstance(la, Var) or pa != la:
            return False
    return True


def _bind(pattern: Literal, e: Literal) -> dict | None:
    """Bindings of ``pattern``'s variables making it ``e`` (e's variables bind nothing)."""
    if pattern.pred != e.pred or len(pattern.args) != len(e.args):
        return None
    b: dict = {}
    for pa, ea in zip(pattern.args, e.args, strict=True):
        if isinstance(pa, Var):
            if isinstance(ea, Var):
                continue
            if b.setdefault(pa, ea) != ea:
                return None
        elif not isinstance(ea, Var) and pa != ea:
            return None
    return b


def _pattern(lit: Literal, b: dict) -> Literal:
    """``lit`` (made positive) with bound variables replaced; the rest stay variables."""
    return Literal(lit.pred, tuple(b.get(a, a) if isinstance(a, Var) else a for a in lit.args))


def _canonical(lit: Literal) -> Literal:
    """``lit`` with its variables renamed ?_1, ?_2, ... in order (patterns compared as such)."""
    names: dict = {}
    return Literal(lit.pred, tuple(names.setdefault(a, Var(f"_{len(names) + 1}"))
                                   if isinstance(a, Var) else a for a in lit.args))


def _shape(actions) -> tuple:
    """The names and numbers of arguments of ``actions``, in order."""
    return tuple((a.name, len(a.args)) for a in actions)


def _action_binding(skill, actions) -> dict | None:
    """The binding of primitive ``skill``'s variables when its :actions are exactly
    ``actions`` (ground), or None (another action, an expression argument)."""
    if len(skill.actions) != len(actions):
        return None
    b: dict = {}
    for t, a in zip(skill.actions, actions, strict=True):
        if t.name != a.name or len(t.args) != len(a.args):
            return None
        for ta, aa in zip(t.args, a.args, strict=True):
            if isinstance(ta, Expr):
                return None
            if isinstance(ta, Var):
                if b.setdefault(ta, aa) != aa:
                    return None
            elif ta != aa:
                return None
    return b
