"""The teleo program of a PDDL domain (`teleo pddl program`, docs/pddl.md):

* each predicate a primitive concept over its atoms' percepts (perception.py):
  ``((on ?x ?y) :percepts ((on _ arg1 ?x arg2 ?y)))``;
* each operator one primitive skill per add effect, the effect its head (ICARUS indexes a skill
  by the concept it achieves; seed 000 writes an action with two effects as one clause per
  effect, as programs/blocks.tlp does), each with the operator's parameters bound by object
  percepts of their types, its preconditions as ``:start`` (equality as the tests ``(= ?x ?y)``
  and ``(<> ?x ?y)``) and the operator as its one action ``(*stack ?x ?y)``. A comment above the
  clauses lists the operator's add and delete effects, and each clause states them as
  ``:effects`` (the other adds, the deletes as ``(not L)``), from which the engine knows what
  the action achieves and undoes (agents/lang/execution/effects.py). An operator
  without add effects achieves no concept and has no skill (a comment says so);
* with a problem, its goal as the program's one conjunctive goal ``(and ...)``, or, for a
  scenario, as the text to post (``goal_text``).

The program reads the world's percepts only, so a user's own concepts and skills go beside it
(``extra`` text, appended, or a second file joined the same way)."""

from __future__ import annotations

import textwrap
from itertools import product

from world.pddl.perception import ATOM, OBJECT
from world.pddl.task import DomainModel, Lit, Operator, Task


def concept_clause(pred: str, params: tuple[tuple[str, tuple[str, ...]], ...]) -> str:
    """The primitive concept of one predicate: ``((on ?x ?y) :percepts ((on _ arg1 ?x arg2
    ?y)))``."""
    names = [v for v, _ in params]
    head = "(" + " ".join([pred, *names]) + ")"
    pattern = "(" + " ".join([pred, ATOM, *[f"arg{k} {v}" for k, v in
                                           enumerate(names, start=1)]]) + ")"
    return f"  ({head}\n   :percepts ({pattern}))"


def negations(model: DomainModel, task: Task | None = None) -> dict[str, str]:
    """predicate -> the name of its negation's concept (``not-p``), for each predicate that a
    precondition (or ``task``'s goal) requires false: the solver pursues only positive
    literals, so ``(not (broken ?v))`` becomes the concept ``(not-broken ?v)``, which the
    operators deleting ``broken`` achieve."""
    names = {p for p, _ in model.predicates}
    lits = [lit for op in model.operators for lit in op.pre] + list(task.goal if task else ())
    out: dict[str, str] = {}
    for lit in lits:
        if lit.negated and lit.pred != "=" and lit.pred not in out:
            name = f"not-{lit.pred}"
            while name in names:
                name += "-"
            out[lit.pred] = name
    return out


def negation_clause(model: DomainModel, pred: str, name: str) -> str:
    """The concept of ``pred``'s negation over the objects of its parameters' types."""
    params = dict(model.predicates)[pred]
    names = [v for v, _ in params]
    percepts = " ".join(f"({OBJECT} {v} type {t[0] if len(t) == 1 else 'object'})"
                        for v, t in params)
    head = "(" + " ".join([name, *names]) + ")"
    core = "(" + " ".join([pred, *names]) + ")"
    lines = [f"  ({head}"] + ([f"   :percepts ({percepts})"] if percepts else [])
    return "\n".join(lines) + f"\n   :relations ((not {core})))"


def _condition(lit: Lit, neg: dict[str, str]) -> str:
    if lit.pred == "=":
        return f"({'<>' if lit.negated else '='} {lit.args[0]} {lit.args[1]})"
    if lit.negated and lit.pred in neg:
        return "(" + " ".join([neg[lit.pred], *lit.args]) + ")"
    return lit.text()


def static_predicates(model: DomainModel) -> frozenset[str]:
    """The predicates no operator adds or deletes: true or false for a whole problem."""
    changed = {lit.pred for op in model.operators for lit in (*op.add, *op.delete)}
    return frozenset(p for p, _ in model.predicates if p not in changed)


def _atom_pattern(lit: Lit) -> str:
    return "(" + " ".join([lit.pred, ATOM, *[f"arg{k} {a}" for k, a in
                                            enumerate(lit.args, start=1)]]) + ")"


def skill_clauses(op: Operator, neg: dict[str, str] | None = None,
                  static: frozenset[str] = frozenset()) -> list[str]:
    """The primitive skills of one operator: one per add effect, and one per delete effect of a
    predicate with a negation concept in ``neg`` (for each `either` choice). A precondition of
    a ``static`` predicate is matched among the :percepts too, first: it holds now or never,
    and it narrows the objects a parameter can take before the others are tried (an untyped
    domain's `(satellite ?s)`)."""
    neg = neg or {}
    adds = " ".join(a.text() for a in op.add) or "nothing"
    dels = " ".join(d.text() for d in op.delete) or "nothing"
    action = "(" + " ".join([f"*{op.name}", *[v for v, _ in op.params]]) + ")"
    made = [a.text() for a in op.add] + \
        ["(" + " ".join([neg[d.pred], *d.args]) + ")" for d in op.delete
         if d.pred in neg and d not in op.add]
    unmade = [f"(not {d.text()})" for d in op.delete if d not in op.add] + \
        ["(not (" + " ".join([neg[a.pred], *a.args]) + "))" for a in op.add if a.pred in neg]
    note = f"{action}: adds {adds}; deletes {dels}"
    if not made:
        note += " (no skill: it achieves no concept)"
    out = ["\n".join(textwrap.wrap(note, 95, initial_indent="  ; ", subsequent_indent="  ;   ",
                                   break_on_hyphens=False))]
    if not made:
        return out
    start = " ".join(_condition(p, neg) for p in op.pre)
    fixed = [_atom_pattern(p) for p in op.pre if p.pred in static and not p.negated]
    for types in product(*[t for _, t in op.params]):
        percepts = " ".join([*fixed, *(f"({OBJECT} {v} type {t})" for (v, _), t in
                                       zip(op.params, types, strict=True))])
        for head in made:
            lines = [f"  ({head}"]
            if percepts:
                lines.append(f"   :percepts ({percepts})")
            if start:
                lines.append(f"   :start ({start})")
            lines.append(f"   :actions ({action})")
            effects = [m for m in made if m != head] + unmade
            if effects:
                lines[-1] += f"\n   :effects ({' '.join(effects)})"
            lines[-1] += ")"
            out.append("\n".join(lines))
    return out


def goal_text(task: Task) -> str:
    """The problem's goal as one teleo goal: ``(and L1 L2 ...)``, a single literal as itself;
    a negated literal as its negation concept's (``negations``)."""
    neg = negations(task.domain, task)
    lits = [_condition(g, neg) for g in task.goal]
    if len(lits) == 1:
        return lits[0]
    return "(and " + " ".join(lits) + ")"


def program_text(model: DomainModel, task: Task | None = None, extra: str = "",
                 source: str = "", goals: bool = True) -> str:
    """The whole program; with ``task`` the negations its goal needs and (``goals``) its goal
    as the goals section; ``extra`` appended."""
    types = " ".join(sorted({t for t, _ in model.types} | {"object"}))
    actions = " ".join("(" + " ".join([f"*{o.name}", *[v for v, _ in o.params]]) + ")"
                       for o in model.operators)
    head = [f"The PDDL domain {model.name}{f' ({source})' if source else ''}, written by "
            f"`teleo pddl program` (docs/pddl.md).",
            f"Percepts: (object NAME type T) for each object and each of its types (types: "
            f"{types}); an atom (p a b) as (p _ arg1 a arg2 b), (p) as (p _).",
            f"Actions: {actions}", *(f"Note: {n}." for n in model.notes)]
    head = [line for text in head for line in textwrap.wrap(
        text, 97, initial_indent="; ", subsequent_indent=";   ", break_on_hyphens=False)]
    head.append("")
    neg = negations(model, task)
    concepts = [concept_clause(p, ps) for p, ps in model.predicates] + \
        [negation_clause(model, p, name) for p, name in neg.items()]
    static = static_predicates(model)
    skills = [c for op in model.operators for c in skill_clauses(op, neg, static)]
    text = "\n".join(head) + "(concepts\n" + "\n".join(concepts) + ")\n\n"
    body = "\n".join(skills)
    # a comment last (an operator with no skill) would swallow the closing parenthesis
    close = "\n  )" if body.rsplit("\n", 1)[-1].lstrip().startswith(";") else ")"
    text += "(skills\n" + body + close + "\n"
    if task is not None and task.goal and goals:
        text += f"\n; the goal of problem {task.name}\n(goals\n  {goal_text(task)})\n"
    if extra:
        text += "\n" + extra.rstrip() + "\n"
    return text
