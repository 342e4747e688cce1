"""Skill learning from the goal stack (seed 000, "Problem Solving and Skill Learning"): when
an entry of a goal stack is achieved, a new skill is made from the decision recorded for it.

* The head is the entry's goal, generalised (seed 000: "a generalized version of the goal in
  which constants are replaced by variables"): every constant of the goal that is the id of a
  percept becomes a variable (the same constant the same variable), bound by a :percepts
  pattern of that percept's type. An object the body names and the goal does not becomes a
  variable only when a positive :start literal ties it to one that is (``(clear ?b1)`` with
  ``:start ((on ?b2 ?b1))``: ?b2 is the block on ?b1, whichever it is); otherwise it stays a
  constant, so the skill never applies to objects its start does not determine (a
  variable bound by a type pattern alone would make the skill "apply" to any block). Other
  constants (numbers, names no percept carries) stay as written.
* Skill chaining (off skill S, whose start was false): the subgoals are the start conditions
  of S that had to be achieved, in the order achieved (in the seed, the head of the skill that
  achieved S's start), then S's head (the goal); the start is the start of the skill that
  achieved the first of them, plus the conditions of S that held throughout.
* Concept chaining: the subgoals are the subconcepts that were achieved, in the order
  achieved; the start is the subconcepts that held initially. A subconcept that held
  initially, became false and was achieved again (Figure 3: ``(hand-empty)`` after
  ``(unstack C B)``) counts as achieved: it is a subgoal, in the order achieved, and not part
  of the start. Otherwise the skill could not work: its start would demand a condition its
  own first subgoal undoes, and nothing would restore it (the seed's learned
  ``(unstackable ?b ?from)`` skill has ``(hand-empty)`` as its last subgoal).
* An entry achieved by executing an existing skill directly (no decision) teaches nothing;
  a skill equal to one the program has (up to variable names, :percepts aside) is not added.
* A conjunctive goal teaches nothing itself (no skill has a conjunction as its head): the
  skills are learned for the conjuncts and subgoals below it.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..core.program import Skill
from ..core.terms import Expr, Literal, PerceptPattern, Test, Var
from ..execution.effects import undone_by
from .state import CONCEPT, CONJUNCTION, StackEntry, condition, literal
from .task import Task


@dataclass(frozen=True, slots=True)
class Learned:
    """A skill learned from one stack entry: ``skill`` (generalised), ``text`` (program
    syntax, with a comment saying when and from which problem), ``start`` (its start, ground,
    for the parent entry's skill), ``duplicate`` (the name of an equal skill already known,
    in which case nothing is added)."""

    skill: Skill
    text: str
    start: tuple[str, ...]
    duplicate: str = ""


def learn(task: Task, entry: StackEntry, comment: str, known: dict[str, str]
          ) -> Learned | None:
    """The skill ``entry``'s decision teaches now that its goal holds, or None when there is
    none (no decision, nothing was achieved through it, or the goal holds through another
    definition than the one chained on).
    ``known``: canonical key -> skill name of every skill known (extended with this one)."""
    way = entry.decision
    if way is None or way.kind == CONJUNCTION or (
            way.kind == CONCEPT and not all(task.holds(c) for c in way.conditions)):
        return None   # (a skill's start may well be false once the skill has run)
    achieved = [c for c in entry.order if c in way.conditions]
    if not achieved:
        return None
    held = [c for c in way.conditions if c in entry.initial and c not in achieved]
    if way.kind == CONCEPT:
        subgoals, start = achieved, held
    else:
        first = dict(entry.starts).get(achieved[0], ())
        subgoals, start = [*achieved, entry.goal], [*first, *held]
    start = _consistent(task, list(dict.fromkeys(
        [*start, *_static(task, entry, achieved), *_untouched(task, entry, achieved)])))
    # a subgoal achieved on the side (by a path the executive found for another goal) left
    # no start: what it needed is not known, so its objects stay constants (else the skill
    # would fly a plane to that package's airport for any package, of any city)
    side = {x for a in achieved if a not in dict(entry.starts) for x in _objects(a)} \
        if way.kind != CONCEPT else set()
    skill = generalise(task, literal(entry.goal), [condition(c) for c in start],
                       [literal(c) for c in subgoals], side)
    key = canonical(skill)
    duplicate = known.get(key, "")
    if not duplicate:
        known[key] = f"learned {skill.head.pred}"
    return Learned(skill, f"; {comment}\n{skill_text(skill)}", tuple(start), duplicate)


def _static(task: Task, entry: StackEntry, achieved: list[str]) -> list[str]:
    """The static conditions (``static``) of the starts of the skills that achieved the
    subgoals after the first: they held when the new skill began, since nothing changes them,
    and without them it would apply where a later step cannot (a truck to an airport of
    another city, when its drive needs (in-city ?from ?city) (in-city ?to ?city))."""
    starts = dict(entry.starts)
    named = {x for c in (entry.goal, *achieved, *starts.get(achieved[0], ()))
             for x in _objects(c)} if achieved else set()
    return [c for a in achieved[1:] for c in starts.get(a, ())
            if static(task, c) and named & _objects(c)]


def _untouched(task: Task, entry: StackEntry, achieved: list[str]) -> list[str]:
    """The start conditions of the skills that achieved the subgoals after the first that
    name no object the subgoals before them, or their skills' starts, name: nothing the earlier
    steps did touched them, so they held when the new skill began (seed 000's start, the first
    step's start alone, would let the skill fly a plane to load a package that no truck can
    bring to the airport; the package's place and its truck are part of the start)."""
    starts = dict(entry.starts)
    out: list[str] = []
    touched: set = set()
    goal = _objects(entry.goal)
    for k, a in enumerate(achieved):
        if k:
            out += [c for c in starts.get(a, ()) if c not in achieved and
                    isinstance(cond := condition(c), Literal) and not cond.negated and
                    (not touched & set(cond.args) or
                     goal & set(cond.args) and _kept(task, cond, achieved[:k]))
                    and (cond.args or static(task, c))]
        touched |= {x for c in (a, *starts.get(a, ())) for x in _objects(c)}
    return out


def _kept(task: Task, cond: Literal, earlier: list[str]) -> bool:
    """Whether the program's effects say that achieving none of ``earlier`` changes the
    ground ``cond`` (one about an object of the goal): depot's crate at the distributor
    stays there while the truck drives there (both name the place), so it belongs to the
    start of loading it there. (Not for the other objects: a truck at the airport a later
    step needs may have been driven there by that step.) Only where the effect model is
    complete (``_stated``): a program whose skills do not state their effects predicts too
    little to vouch for it (blocks: nothing says whether achieving ``(clear C)`` leaves the
    concept ``(pickupable B T)``, with its ``(hand-empty)``, alone; asking for it made the
    skill learned for ``(on B C)`` too narrow to apply again)."""
    if cond.variables() or not _stated(task, cond.pred):
        return False
    lits = [literal(a) for a in earlier]
    return all(_stated(task, x.pred) for x in lits) and not any(
        cond == x or undone_by(cond, task.effects.undoes(x)) or
        undone_by(cond, tuple(task.effects.achieved_with(x))) for x in lits)


def _stated(task: Task, pred: str) -> bool:
    """Whether the program's effects of ``pred`` are all known: no concept derives it by
    relations, and the primitive skills that make it (head or effect) state their effects."""
    if _derived(task, pred):
        return False
    makers = [s for s in task.program.skills if s.head.pred == pred or
              any(e.pred == pred and not e.negated for e in s.effects)]
    return bool(makers) and all(s.kind == "primitive" and s.effects for s in makers)


def _consistent(task: Task, start: list[str]) -> list[str]:
    """``start`` without each condition that one before it excludes: achieving the earlier
    ground literal undoes it (the program's effects; ``(handempty)`` undoes ``(holding b1)``),
    so both never hold at once and a start asking for both would never apply. Seed 000's own
    start (the first step's) comes first and is kept; what the later steps add yields."""
    out: list[str] = []
    for c in start:
        cond = condition(c)
        if isinstance(cond, Literal) and not cond.negated and not cond.variables() and any(
                _excludes(task, x, cond) for x in map(condition, out)
                if isinstance(x, Literal) and not x.negated and not x.variables()):
            continue
        out.append(c)
    return out


def _excludes(task: Task, a: Literal, b: Literal) -> bool:
    """Whether the ground literals ``a`` and ``b`` exclude each other: achieving either undoes
    the other (``(handempty)`` and ``(holding b1)``). One way is not enough: what the skill
    that achieves ``a`` happens to delete may well hold beside ``a`` (elevators: a passenger
    left at a floor, and a lift's passenger count, which every leave changes)."""
    return undone_by(b, task.effects.undoes(a)) and undone_by(a, task.effects.undoes(b))


def _objects(text: str) -> set:
    """The objects a start condition's literal names; none for a test such as ``(not (= ?a
    ?b))``, which reads objects but changes and ties none."""
    cond = condition(text)
    return set(cond.args) if isinstance(cond, Literal) else set()


def static(task: Task, text: str) -> bool:
    """True for a positive literal whose predicate no skill achieves and no concept defines
    by relations: only the world's percepts make it, and no action changes it."""
    cond = condition(text)
    if not isinstance(cond, Literal) or cond.negated:
        return False
    return not task.program.skills_for(cond.pred) and not _derived(task, cond.pred)


def _derived(task: Task, pred: str) -> bool:
    """Whether a concept derives ``pred`` from relations or tests (not only from percepts)."""
    return any(c.relations or c.tests for c in task.program.concepts.get(pred, ()))


def generalise(task: Task, head: Literal, start: list, subgoals: list[Literal],
               keep: set | frozenset = frozenset()) -> Skill:
    """A skill with the percept ids of ``head`` replaced by variables named after their
    percept type (``?b1`` for the first block), consistently, and with them every percept id
    that a positive :start literal ties to one replaced (see the module docstring); the ids
    in ``keep`` stay constants."""
    names: dict[object, Var] = {}
    taken = {v.name for c in (head, *start, *subgoals) for v in c.variables()}
    types: list[tuple[Var, str, tuple]] = []
    ids = {x for x in head.args if isinstance(x, str) and task.type_of(x) is not None} - keep
    ties = [c for c in start if isinstance(c, Literal) and not c.negated]
    grown = True
    while grown:
        grown = False
        for c in ties:
            mine = {x for x in c.args if isinstance(x, str) and task.type_of(x) is not None
                    } - keep
            if mine & ids and not mine <= ids:
                ids |= mine
                grown = True

    def var(x: object) -> object:
        if isinstance(x, Var) or x in names:
            return names.get(x, x)
        if x not in ids:
            return x
        kind = task.type_of(x)
        n = 1
        while f"{kind[0]}{n}" in taken:
            n += 1
        taken.add(f"{kind[0]}{n}")
        names[x] = Var(f"{kind[0]}{n}")
        types.append((names[x], kind, task.attrs_of(x, kind)))
        return names[x]

    def lit(c: Literal) -> Literal:
        return Literal(c.pred, tuple(var(a) for a in c.args), c.negated)

    def expr(e: object) -> object:
        return Expr(e.op, tuple(expr(a) for a in e.args)) if isinstance(e, Expr) else var(e)

    new_head = lit(head)
    new_subgoals = tuple(lit(g) for g in subgoals)
    new_start = tuple(lit(c) if isinstance(c, Literal) else Test(expr(c.expr)) for c in start)
    percepts = tuple(PerceptPattern(kind, v, attrs) for v, kind, attrs in types)
    return Skill(new_head, percepts, new_start, (), new_subgoals)


def canonical(skill: Skill) -> str:
    """The skill with its variables renamed in order of appearance (head, subgoals, actions,
    start, requires): equal keys mean the same skill up to variable names and :percepts."""
    names: dict[Var, str] = {}

    def term(x: object) -> str:
        if isinstance(x, Var):
            return names.setdefault(x, f"?v{len(names)}")
        if isinstance(x, Expr):
            return "(" + " ".join([x.op, *(term(a) for a in x.args)]) + ")"
        return repr(x)

    def cond(c: object) -> str:
        if isinstance(c, Test):
            return term(c.expr)
        core = "(" + " ".join([c.pred, *(term(a) for a in c.args)]) + ")"
        return f"(not {core})" if c.negated else core

    parts = [cond(skill.head), " ".join(cond(g) for g in skill.subgoals),
             " ".join("(" + " ".join([a.name, *(term(x) for x in a.args)]) + ")"
                      for a in skill.actions)]
    parts += [" ".join(sorted(cond(c) for c in skill.start)),
              " ".join(sorted(cond(c) for c in skill.requires))]
    return " | ".join(parts)


def skill_text(skill: Skill) -> str:
    """A learned skill in program syntax (seed 000, Table 1 layout)."""
    lines = [f"({skill.head}"]
    if skill.percepts:
        lines.append(" :percepts (" + " ".join(map(str, skill.percepts)) + ")")
    if skill.start:
        lines.append(" :start (" + " ".join(map(str, skill.start)) + ")")
    lines.append(" :subgoals (" + " ".join(map(str, skill.subgoals)) + "))")
    return "\n".join(lines)
