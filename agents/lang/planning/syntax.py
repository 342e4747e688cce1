"""The planner's program sections (seed 003; docs/language.md, "Planning"): contributed to
the parser by the planner's Mechanism (planning/mechanism.py) and kept in ``Program.sections``.

``(operators CLAUSE ...)``: PRODIGY's operators as skill clauses: the head is the primary
effect, :start the preconditions, :actions the commands that execute it, plus
``:operator (name ?param ...)``, ``:effects (lit ... (not lit) ...)`` (the head is an effect
even when not listed; a variable bound nowhere in a negated effect means any value) and
``:on-failure (actions)``, announced when the operator ends without its primary effect.

``(requests CLAUSE ...)``: what the planner adds to its state model when a request arrives
(seed 003, section 4: "Add knowledge to state model, create top-level goal"):
``((goal-pattern) :percepts (...) :start (...) :knowledge (facts))``.

``(control-rules RULE ...)``: PRODIGY's search control rules, seed 003 Table 2's form with
``?var`` for ``<var>``: ``(control-rule NAME (if COND) (then select|prefer|reject
goal|operator|bindings ARGS))``, and ``(travel ...)``, where the robot is and how far apart
places are, for ROGUE's execution-driven choice of the next action (section 4).

Each parsed item answers ``define(checker)`` (the planner's own predicates) and
``check(checker)`` (file:line:col diagnostics), called by agents/lang/reading/checks.py; the
sections
are read by agents/lang/planning/reader.py.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..core.program import Skill
from ..core.terms import ActionTemplate, Literal, Loc, PerceptPattern, Var

GOAL_META = ("candidate-goal", "ancestor-is-top-priority-goal",
             "compatible-with-top-priority-goal")
LITERAL_META = ("current-goal", "true-in-state")
META = (*GOAL_META, *LITERAL_META, "candidate-operator", "closer")
VERBS = ("select", "prefer", "reject")
KINDS = ("goal", "operator", "bindings")


@dataclass(frozen=True, slots=True)
class OperatorSpec:
    """One operator: ``skill`` (head, :percepts, :start, :actions as parsed for a skill),
    ``name`` and ``params`` (``(goto-pickup-loc ?person ?room)``), ``effects`` (the head
    first), ``on_failure`` (commands announced when it ends without its primary effect)."""

    skill: Skill
    name: str
    params: tuple
    effects: tuple[Literal, ...]
    on_failure: tuple[ActionTemplate, ...]
    loc: Loc

    def define(self, checker: Any) -> None:
        for e in self.effects:
            if e.pred not in checker.arity:
                checker.define(Literal(e.pred, e.args, False, e.loc))

    def check(self, checker: Any) -> None:
        s = self.skill
        checker.check_skill(s)
        bound = set(s.head.variables()) | {v for p in s.percepts for v in p.variables()}
        bound |= {v for c in s.start if isinstance(c, Literal) and not c.negated
                  for v in c.variables()}
        where = f"operator {self.name}"
        checker.unbound({a for a in self.params if isinstance(a, Var)} - bound, self.loc,
                        f"the parameters of {where}",
                        "bind it in the head, :percepts or :start", bound)
        for e in self.effects:
            checker.use(e, f":effects of {where}")
            if not e.negated:
                checker.unbound(e.variables() - bound, e.loc, f"effect {e} of {where}",
                                "bind it in the head, :percepts or :start (only a negated "
                                "effect may leave a variable open: any value)", bound)
        for a in self.on_failure:
            checker.unbound(a.variables() - bound, a.loc, f"action {a} of {where}",
                            "bind it in the head, :percepts or :start", bound)

    @property
    def head(self) -> Literal:
        return self.skill.head


@dataclass(frozen=True, slots=True)
class RequestSpec:
    """What a request matching ``head`` adds to the state model when it arrives."""

    head: Literal
    percepts: tuple[PerceptPattern, ...]
    start: tuple
    knowledge: tuple[Literal, ...]
    loc: Loc

    def define(self, checker: Any) -> None:
        for k in self.knowledge:
            if k.pred not in checker.arity:
                checker.define(k)

    def check(self, checker: Any) -> None:
        checker.use(self.head, "a (requests ...) clause head")
        bound = set(self.head.variables()) | {v for p in self.percepts
                                              for v in p.variables()}
        for c in self.start:
            if isinstance(c, Literal):
                checker.use(c, "the :start of a (requests ...) clause")
                if not c.negated:
                    bound |= c.variables()
        for k in self.knowledge:
            checker.use(k, "the :knowledge of a (requests ...) clause")
            checker.unbound(k.variables() - bound, k.loc, f"knowledge {k}",
                            "bind it in the head, :percepts or :start", bound)


@dataclass(frozen=True, slots=True)
class Meta:
    """A condition of a control rule: a meta-predicate with its arguments (terms, literals
    or operator patterns), or ``and``/``or``/``not`` over ``args`` (Meta values)."""

    name: str
    args: tuple
    loc: Loc | None = None

    def variables(self) -> set[Var]:
        out: set[Var] = set()
        for a in self.args:
            out |= a.variables() if isinstance(a, Meta | Literal) else \
                ({a} if isinstance(a, Var) else set())
        return out


@dataclass(frozen=True, slots=True)
class ControlRule:
    """``(control-rule NAME (if COND) (then VERB KIND ARGS))``; ARGS are terms (goal),
    operator names (operator) or operator patterns such as (schedule-meeting ?room)
    (bindings); prefer takes two: the preferred one first."""

    name: str
    cond: Meta
    verb: str
    kind: str
    args: tuple
    loc: Loc

    def define(self, checker: Any) -> None:
        pass

    def check(self, checker: Any) -> None:
        _check_cond(checker, self.cond, self.name)
        bound = _positive_vars(self.cond)
        for a in self.args:
            vs = a.variables() if isinstance(a, Literal) else ({a} if isinstance(a, Var)
                                                               else set())
            checker.unbound(vs - bound, self.loc, f"the (then ...) of control rule {self.name}",
                            "bind it in a positive condition of (if ...)", bound)
        names = _operator_names(checker)
        ops = [a.pred for a in self.args if isinstance(a, Literal)] if self.kind == "bindings" \
            else [a for a in self.args if isinstance(a, str)] if self.kind == "operator" else []
        for op in ops:
            if op not in names:
                checker.err(self.loc, f"control rule {self.name}: no operator {op!r} "
                            f"(operators: {' '.join(sorted(names)) or 'none'})")


@dataclass(frozen=True, slots=True)
class Travel:
    """Where the robot is (``location``, a literal whose one variable is the place) and how
    far apart places are: ``between`` a percept pattern with the two places and the distance
    as its variables in that order, ``from_here`` one with a place and the distance from the
    robot's position; ``detour`` [m]: how much a lower-priority request may add to the travel
    of the top-priority ones and still be compatible with them (seed 003, Table 2);
    ``carrying`` (optional) a literal with one instance per thing the robot carries, and
    ``capacity`` a percept pattern whose last variable is how many it can carry: a step that
    adds a ``carrying`` instance fills a place, one that deletes it frees one, and no merged
    order carries more than the capacity."""

    location: Literal
    between: PerceptPattern
    from_here: PerceptPattern
    detour: float
    loc: Loc
    carrying: Literal | None = None
    capacity: PerceptPattern | None = None

    def define(self, checker: Any) -> None:
        pass

    def check(self, checker: Any) -> None:
        checker.use(self.location, "the :location of (travel ...)")
        for what, pattern, want in ((":between", self.between, 3),
                                    (":from-here", self.from_here, 2)):
            if len(_ordered_vars(pattern)) != want:
                checker.err(self.loc, f"(travel ...) {what} {pattern}: expected {want} "
                            f"variables (places, then the distance), got "
                            f"{len(_ordered_vars(pattern))}")
        if len(self.location.variables()) != 1:
            checker.err(self.loc, f"(travel ...) :location {self.location}: expected one "
                        "variable, the place")
        if self.carrying is not None:
            checker.use(self.carrying, "the :carrying of (travel ...)")
        if self.capacity is not None and not _ordered_vars(self.capacity):
            checker.err(self.loc, f"(travel ...) :capacity {self.capacity}: expected a "
                        "variable for how many the robot can carry (its last one)")


def _ordered_vars(p: PerceptPattern) -> list[Var]:
    out = [p.id] if isinstance(p.id, Var) else []
    out += [v for _, v in p.attrs if isinstance(v, Var)]
    return list(dict.fromkeys(out))


def between_vars(p: PerceptPattern) -> list[Var]:
    """The variables of a travel pattern in order of appearance."""
    return _ordered_vars(p)


def _operator_names(checker: Any) -> set[str]:
    return {o.name for o in checker.parts.sections.get("operators", ())}


def _check_cond(checker: Any, c: Meta, rule: str) -> None:
    if c.name in ("and", "or", "not"):
        for x in c.args:
            _check_cond(checker, x, rule)
        return
    for a in c.args:
        if isinstance(a, Literal) and c.name in LITERAL_META:
            checker.use(a, f"control rule {rule}")
        elif isinstance(a, Literal) and a.pred not in _operator_names(checker):
            checker.err(c.loc, f"control rule {rule}: ({c.name} {a}): no operator "
                        f"{a.pred!r}")


def _positive_vars(c: Meta) -> set[Var]:
    if c.name == "not":
        return set()
    if c.name == "or":
        sets = [_positive_vars(x) for x in c.args]
        return set.intersection(*sets) if sets else set()
    if c.name == "and":
        return set().union(*(_positive_vars(x) for x in c.args))
    return c.variables()
