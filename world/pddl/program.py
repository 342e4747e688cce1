"""The teleo program of a PDDL domain (`teleo pddl program`, docs/pddl.md):

* each predicate a primitive concept over its atoms' percepts (perception.py):
  ``((on ?x ?y) :percepts ((on ?x arg2 ?y)))``;
* each operator one primitive skill per add effect, the effect its head (ICARUS indexes a skill
  by the concept it achieves; seed 000 writes an action with two effects as one clause per
  effect, as programs/blocks.tlp does), each with the operator's parameters bound by object
  percepts of their types, its preconditions as ``:start`` (equality as the tests ``(= ?x ?y)``
  and ``(<> ?x ?y)``) and the operator as its one action ``(*stack ?x ?y)``. A comment above the
  clauses lists the operator's add and delete effects; the engine learns what an action achieves
  from the heads of the clauses that perform it (agents/lang/execution/effects.py). An operator
  without add effects achieves no concept and has no skill (a comment says so);
* with a problem, its goal as the program's one conjunctive goal ``(and ...)``, or, for a
  scenario, as the text to post (``goal_text``).

The program reads the world's percepts only, so a user's own concepts and skills go beside it
(``extra`` text, appended, or a second file joined the same way)."""

from __future__ import annotations

from itertools import product

from world.pddl.perception import NULLARY, OBJECT
from world.pddl.task import DomainModel, Lit, Operator, Task


def concept_clause(pred: str, params: tuple[tuple[str, tuple[str, ...]], ...]) -> str:
    """The primitive concept of one predicate."""
    names = [v for v, _ in params]
    head = "(" + " ".join([pred, *names]) + ")"
    if not names:
        pattern = f"({pred} {NULLARY})"
    else:
        pattern = "(" + " ".join([pred, names[0], *[f"arg{k} {v}" for k, v in
                                                     enumerate(names[1:], start=2)]]) + ")"
    return f"  ({head}\n   :percepts ({pattern}))"


def _condition(lit: Lit) -> str:
    if lit.pred == "=":
        return f"({'<>' if lit.negated else '='} {lit.args[0]} {lit.args[1]})"
    return lit.text()


def skill_clauses(op: Operator) -> list[str]:
    """The primitive skills of one operator (one per add effect and `either` choice)."""
    adds = " ".join(a.text() for a in op.add) or "nothing"
    dels = " ".join(d.text() for d in op.delete) or "nothing"
    action = "(" + " ".join([f"*{op.name}", *[v for v, _ in op.params]]) + ")"
    out = [f"  ; {action}: adds {adds}; deletes {dels}"]
    if not op.add:
        out[0] += " (no skill: it achieves no concept)"
        return out
    start = " ".join(_condition(p) for p in op.pre)
    for types in product(*[t for _, t in op.params]):
        percepts = " ".join(f"({OBJECT} {v} type {t})" for (v, _), t in zip(op.params, types,
                                                                             strict=True))
        for add in op.add:
            lines = [f"  ({add.text()}"]
            if percepts:
                lines.append(f"   :percepts ({percepts})")
            if start:
                lines.append(f"   :start ({start})")
            lines.append(f"   :actions ({action}))")
            out.append("\n".join(lines))
    return out


def goal_text(task: Task) -> str:
    """The problem's goal as one teleo goal: ``(and L1 L2 ...)``, a single literal as itself."""
    lits = [g.text() for g in task.goal]
    if len(lits) == 1:
        return lits[0]
    return "(and " + " ".join(lits) + ")"


def program_text(model: DomainModel, task: Task | None = None, extra: str = "",
                 source: str = "") -> str:
    """The whole program; with ``task`` its goal as the goals section; ``extra`` appended."""
    objects = ", ".join(f"({OBJECT} NAME type {t})" for t in
                        sorted({t for t, _ in model.types} | {"object"}))
    head = [f"; The PDDL domain {model.name}{f' ({source})' if source else ''}, written by "
            f"`teleo pddl program` (docs/pddl.md).",
            f"; Percepts: an object once per type it has: {objects};",
            "; an atom (p a b c) as (p a arg2 b arg3 c), (p a) as itself, (p) as (p true).",
            "; Actions: " + " ".join("(" + " ".join([f"*{o.name}", *[v for v, _ in o.params]])
                                     + ")" for o in model.operators),
            ""]
    concepts = [concept_clause(p, ps) for p, ps in model.predicates]
    skills = [c for op in model.operators for c in skill_clauses(op)]
    text = "\n".join(head) + "(concepts\n" + "\n".join(concepts) + ")\n\n"
    text += "(skills\n" + "\n".join(skills) + ")\n"
    if task is not None and task.goal:
        text += f"\n; the goal of problem {task.name}\n(goals\n  {goal_text(task)})\n"
    if extra:
        text += "\n" + extra.rstrip() + "\n"
    return text
