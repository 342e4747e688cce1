"""Search control rules (seed 003, section 3: "control rules can select, prefer or reject a
particular goal or action in a particular situation"), evaluated at two of PRODIGY's decision
points (Table 1): which pending goals to work on (``select_goals``), and which operator and
bindings to back-chain on for a literal (``order``). Every rule that fires is recorded, in
the seed's words: ``prefer bindings LOOK-AT-CLOSEST-CONF-ROOM-FIRST (schedule-meeting r-5309)
over (schedule-meeting r-5311)`` (Figure 7).

Conditions are solved left to right over bindings (``?var``), ``not`` as failure to prove:
  (candidate-goal ?g)                      ?g ranges over the pending goals (their ids)
  (ancestor-is-top-priority-goal ?g)       ?g has the top priority (lowest number)
  (compatible-with-top-priority-goal ?g)   merging ?g adds at most the travel :detour to the
                                           top-priority goals' plans (agents/lang/planning/
                                           merge.py)
  (current-goal LIT)                       the literal being back-chained on matches LIT
  (candidate-operator (NAME ARG ...))      an operator instance offered for it
  (true-in-state LIT)                      LIT holds in the (projected) state
  (closer ?a ?b)                           place ?a is nearer than ?b (travel distances)
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from ..core.matcher import match_fact, subst, unify_head
from ..core.store import FactStore
from ..core.terms import Literal, Var, fmt
from ..solving.state import Alternative
from .syntax import ControlRule, Meta


@dataclass
class GoalView:
    """What the goal meta-predicates read: candidate goal ids, and two tests."""

    candidates: list[str]
    top: Callable[[str], bool]
    compatible: Callable[[str], bool]
    shown: Callable[[str], str]


@dataclass
class OperatorView:
    """What the operator meta-predicates read at one back-chaining decision."""

    goal: Literal
    instances: list[Literal]       # (name arg ...) of each alternative, in order
    state: FactStore
    distance: Callable[[str], float]


@dataclass
class Control:
    """The program's control rules; ``firings`` collects what fired, in order."""

    rules: tuple[ControlRule, ...]
    firings: list[str] = field(default_factory=list)

    @property
    def selects_goals(self) -> bool:
        return any(r.kind == "goal" for r in self.rules)

    def select_goals(self, view: GoalView) -> list[str]:
        """The goals to work on, best first: those selected (all when no rule selects),
        less those rejected, ordered by preferences (ties keep ``view.candidates`` order)."""
        chosen, rejected, prefer = set(), set(), []
        for rule in (r for r in self.rules if r.kind == "goal"):
            for b in _solutions(rule.cond, {}, view):
                args = [subst(a, b) for a in rule.args]
                if any(isinstance(a, Var) or a not in view.candidates for a in args):
                    continue
                self._fired(rule, [view.shown(a) for a in args])
                if rule.verb == "select":
                    chosen.add(args[0])
                elif rule.verb == "reject":
                    rejected.add(args[0])
                else:
                    prefer.append((args[0], args[1]))
        # a select rule that fires narrows the choice; one that does not fire leaves it whole
        pool = [g for g in view.candidates if (g in chosen or not chosen) and g not in rejected]
        return _prefer(pool, prefer)

    def order(self, view: OperatorView, alts: tuple[Alternative, ...]
              ) -> tuple[Alternative, ...]:
        """The alternatives for ``view.goal`` after the operator and bindings rules."""
        keys = [_key(i) for i in view.instances]
        selected: set[tuple] = set()
        rejected: set[tuple] = set()
        prefer: list[tuple[tuple, tuple]] = []
        any_select = False
        for rule in (r for r in self.rules if r.kind != "goal"):
            for b in _solutions(rule.cond, {}, view):
                match = [self._matching(rule.kind, a, b, keys) for a in rule.args]
                if any(not m for m in match):
                    continue
                self._fired(rule, [_show(rule.kind, a, b) for a in rule.args])
                if rule.verb == "select":
                    any_select = True
                    selected |= set(match[0])
                elif rule.verb == "reject":
                    rejected |= set(match[0])
                else:
                    prefer += [(x, y) for x in match[0] for y in match[1] if x != y]
        pool = [k for k in keys if (k in selected or not any_select) and k not in rejected]
        order = _prefer(pool, prefer)
        return tuple(alts[keys.index(k)] for k in order)

    def _matching(self, kind: str, arg: object, b: dict, keys: list[tuple]) -> list[tuple]:
        if kind == "operator":
            return [k for k in keys if k[0] == arg]
        pattern = Literal(arg.pred, tuple(subst(a, b) for a in arg.args))
        return [k for k in keys if k[0] == pattern.pred and
                unify_head(pattern, Literal(k[0], k[1])) is not None]

    def _fired(self, rule: ControlRule, shown: list[str]) -> None:
        what = " over ".join(shown) if rule.verb == "prefer" else shown[0]
        text = f"{rule.verb} {rule.kind} {rule.name} {what}"
        if text not in self.firings:
            self.firings.append(text)


def _key(instance: Literal) -> tuple:
    return (instance.pred, instance.args)


def _show(kind: str, arg: object, b: dict) -> str:
    if isinstance(arg, Literal):
        return str(Literal(arg.pred, tuple(subst(a, b) for a in arg.args)))
    return fmt(subst(arg, b))


def _prefer(pool: list, pairs: list[tuple]) -> list:
    """``pool`` reordered so that each preferred element comes before the one it is
    preferred over (a cycle of preferences keeps the given order)."""
    rest, out = list(pool), []
    while rest:
        pick = next((x for x in rest if not any(y != x and (y, x) in pairs and y in rest
                                                 for y in rest)), rest[0])
        out.append(pick)
        rest.remove(pick)
    return out


def _solutions(c: Meta, b: dict, view: GoalView | OperatorView) -> Iterator[dict]:
    if c.name == "and":
        yield from _conj(list(c.args), b, view)
    elif c.name == "or":
        for x in c.args:
            yield from _solutions(x, b, view)
    elif c.name == "not":
        if next(_solutions(c.args[0], b, view), None) is None:
            yield b
    else:
        yield from _meta(c, b, view)


def _conj(conds: list[Meta], b: dict, view) -> Iterator[dict]:
    if not conds:
        yield b
        return
    for nb in _solutions(conds[0], b, view):
        yield from _conj(conds[1:], nb, view)


def _bind(term: object, value: object, b: dict) -> dict | None:
    t = subst(term, b)
    if isinstance(t, Var):
        return {**b, t: value}
    return b if t == value else None


def _meta(c: Meta, b: dict, view) -> Iterator[dict]:
    if isinstance(view, GoalView):
        if c.name == "candidate-goal":
            for g in view.candidates:
                nb = _bind(c.args[0], g, b)
                if nb is not None:
                    yield nb
        elif c.name in ("ancestor-is-top-priority-goal", "compatible-with-top-priority-goal"):
            g = subst(c.args[0], b)
            test = view.top if c.name.startswith("ancestor") else view.compatible
            if not isinstance(g, Var) and g in view.candidates and test(g):
                yield b
        return
    if c.name == "current-goal":
        pattern = Literal(c.args[0].pred, tuple(subst(a, b) for a in c.args[0].args))
        nb = unify_head(pattern, view.goal, dict(b)) if pattern.pred == view.goal.pred \
            and len(pattern.args) == len(view.goal.args) else None
        if nb is not None:
            yield nb
    elif c.name == "candidate-operator":
        pattern = c.args[0]
        for inst in view.instances:
            if inst.pred == pattern.pred and len(inst.args) == len(pattern.args):
                nb = unify_head(Literal(pattern.pred, tuple(subst(a, b) for a in pattern.args)),
                                inst, dict(b))
                if nb is not None:
                    yield nb
    elif c.name == "true-in-state":
        yield from match_fact(c.args[0], b, view.state)
    elif c.name == "closer":
        x, y = (subst(a, b) for a in c.args)
        if not isinstance(x, Var) and not isinstance(y, Var) and \
                view.distance(str(x)) < view.distance(str(y)):
            yield b
