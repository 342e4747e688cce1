"""What an action is known to achieve and to undo, read from the program alone (issue 22: the
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

    # -- actions -----------------------------------------------------------------------------
    def of_actions(self, actions: tuple[Action, ...] | list[Action]
                   ) -> tuple[tuple[Literal, ...], tuple[Literal, ...]]:
        """(achieved literals, undone patterns) of executing ``actions`` in one cycle;
        variables in a pattern stand for any value."""
        key = tuple((a.name, a.args) for a in actions)
        hit = self._actions.get(key)
        if hit is None:
            achieved = tuple(dict.fromkeys(h for s in self.program.skills
                                           if s.kind == "primitive" and s.actions
                                           for h in [_head_of(s, actions)] if h is not None))
            undone = tuple(dict.fromkeys(p for e in achieved for p in self.undoes(e)))
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
        out = list(self._excluded_by(e)) + list(self._excluding(e))
        frontier = list(out)
        for _ in range(CLOSURE):
            frontier = [p for q in frontier for p in self._needing(q) if p not in out]
            out += frontier
        hit = tuple(dict.fromkeys(out))
        if len(self._undoes) < _MAX_CACHE:
            self._undoes[e] = hit
        return hit

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


def _head_of(skill, actions) -> Literal | None:
    """The head of primitive ``skill`` when its :actions are exactly ``actions`` (ground),
    or None (another action, an expression argument, a head variable left open)."""
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
    head = _pattern(skill.head, b)
    return None if head.variables() else head
