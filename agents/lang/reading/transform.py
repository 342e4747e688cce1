"""Program-to-program transformations between seed 000's two notations. Pure.

A prioritized program states its driving laws once, as its goal list (seed 000, "Adding Goal
Priorities"); the original teleoreactive notation has no goal list for them and must encode
every law in every skill (Tables 5 and 6). ``compile_laws`` does that encoding mechanically:

* Every skill that does not belong to a law (see "law skills" below) is kept, with the laws
  added in front of its :requires, most important first (the *main* clause).
* For each law L_k it gets a *twin* right after it: the same head and :percepts, :start
  ``((not L_k) start...)``, :requires ``(L_1 ... L_k-1)`` (only the more important laws) and
  :subgoals ``(L_k head)``: when the law is broken, restore it first, then achieve the head.
  Table 1's at-address skill with the law (at-desired-speed ?self) becomes Table 5 exactly, with
  (not-hitting-pedestrians ?self) above it Table 6 exactly (tests/lang/test_transform.py).
* Law skills (those whose head is a law, and any skill only they reach) are kept as they are:
  they run only while every more important law holds, which the twins' :requires ensure.
  This is how the seed counts (Table 7: 54 + 54 + 3 = 111, 3 x 54 + 3 + 1 = 166).
* The goal list becomes empty: the user's errands are the only top-level goals.

A law with variables, such as (at-desired-speed ?self), means every instance (docs/language.md,
goals with variables); its variables are fixed by percepts (here the `self` percept). In a
skill, a law variable is named by the skill's own variable for a percept of that type (the
skill's (self ?self)), or the percept is added to the skill's :percepts. With one percept of
that type per cycle (a car perceives one `self`), the instance the skill checks is the one
instance of the goal, and the two notations choose the same actions (bench/driving/tables.py checks
this on whole runs). ``drop_laws`` and ``replace_law`` make the prioritized programs for fewer
or other laws (Tables 7 and 8): they change the goal list and the laws' own skills only.
"""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import replace

from ..core.errors import LangError
from ..core.program import GoalSpec, Program, Skill
from ..core.terms import Literal, PerceptPattern, Var


class TransformError(LangError):
    """A program cannot be transformed as asked; the message names the law or skill."""


def compile_laws(program: Program) -> Program:
    """The original-notation program with the same behaviour: the goal list's laws encoded in
    every other skill as a :requires and one twin clause per law (module docstring)."""
    laws = tuple(g.literal for g in program.goals)
    if not laws:
        return program
    kept = _law_skills(program, {law.pred for law in laws})
    skills: list[Skill] = []
    for s in program.skills:
        skills += [s] if s.number in kept else _encode(program, s, laws)
    return _rebuild(program, skills, ())


def drop_laws(program: Program, preds: Collection[str]) -> Program:
    """The prioritized program without the laws ``preds``: their goals and their skills go."""
    _known(program, preds)
    gone = _law_skills(program, set(preds))
    for s in program.skills:
        if s.number in gone:
            continue
        for g in s.subgoals:
            if g.pred in preds:
                raise TransformError(f"skill {s.name} ({s.loc}) has the law {g.pred} as a "
                                     "subgoal; it cannot be dropped")
    skills = [s for s in program.skills if s.number not in gone]
    goals = tuple(g for g in program.goals if g.literal.pred not in preds)
    return _rebuild(program, skills, goals)


def replace_law(program: Program, old: str, new: str) -> Program:
    """The prioritized program with law ``new`` in the place of law ``old`` in the goal list;
    ``old``'s skills go. Both laws must be in the goal list (load the new law's file with the
    program: ``load_program("driving.tlp", "laws/fast.tlp")``)."""
    _known(program, (old, new))
    new_goal = next(g for g in program.goals if g.literal.pred == new)
    goals = tuple(new_goal if g.literal.pred == old else g
                  for g in program.goals if g.literal.pred != new)
    gone = _law_skills(program, {old}) - _law_skills(program, {new})
    return _rebuild(program, [s for s in program.skills if s.number not in gone], goals)


def _known(program: Program, preds: Collection[str]) -> None:
    have = [g.literal.pred for g in program.goals]
    for p in preds:
        if p not in have:
            raise TransformError(f"law {p} is not in the program's goal list "
                                 f"({', '.join(have) or 'empty'})")


def _law_skills(program: Program, preds: set[str]) -> set[int]:
    """Numbers of the skills of the laws ``preds`` and of every skill only they reach."""
    reach, todo = set(preds), list(preds)
    while todo:
        for s in program.skills_for(todo.pop()):
            for g in s.subgoals:
                if g.pred not in reach:
                    reach.add(g.pred)
                    todo.append(g.pred)
    for s in program.skills:
        if s.head.pred not in reach:
            shared = [g.pred for g in s.subgoals if g.pred in reach - preds]
            if shared:
                raise TransformError(f"skill {s.name} ({s.loc}) has the subgoal {shared[0]}, "
                                     "which a law's skills also use; the notations would differ")
    return {s.number for s in program.skills if s.head.pred in reach}


def _encode(program: Program, s: Skill, laws: tuple[Literal, ...]) -> list[Skill]:
    """The main clause and one twin per law for skill ``s`` (seed 000, Tables 5 and 6)."""
    percepts = list(s.percepts)
    tied = tuple(_tie(program, law, s, percepts) for law in laws)
    out = [replace(s, percepts=tuple(percepts), requires=tied + tuple(s.requires))]
    for k, law in enumerate(tied):
        out.append(replace(s, percepts=tuple(percepts),
                           start=(replace(law, negated=True), *s.start),
                           requires=tied[:k], subgoals=(law, s.head), actions=()))
    return out


def _tie(program: Program, law: Literal, s: Skill, percepts: list[PerceptPattern]) -> Literal:
    """``law`` with each variable renamed to the skill's variable for the percept that fixes
    it; adds that percept to ``percepts`` when the skill has none of its type."""
    names = {v.name for v in _variables(s)} | {p.id.name for p in percepts
                                               if isinstance(p.id, Var)}
    args = []
    for i, a in enumerate(law.args):
        if not isinstance(a, Var):
            args.append(a)
            continue
        kind = _instance_type(program, law, i)
        mine = next((p.id for p in percepts if p.type == kind and isinstance(p.id, Var)), None)
        if mine is None:
            mine = Var(_fresh(a.name, names))
            names.add(mine.name)
            percepts.append(PerceptPattern(kind, mine, ()))
        args.append(mine)
    return Literal(law.pred, tuple(args))


def _instance_type(program: Program, law: Literal, i: int) -> str:
    """The percept type whose id fixes argument ``i`` of the law in every clause of its
    concept (the `self` of (at-desired-speed ?self))."""
    kinds = set()
    for c in program.concepts.get(law.pred, ()):
        h = c.head.args[i]
        found = [p.type for p in c.percepts if isinstance(h, Var) and p.id == h]
        if not found:
            raise TransformError(f"law {law}: argument {i + 1} is not fixed by a percept's id "
                                 f"in concept clause {law.pred}#{c.index} ({c.loc})")
        kinds.add(found[0])
    if len(kinds) != 1:
        raise TransformError(f"law {law}: argument {i + 1} is fixed by different percept types "
                             f"({', '.join(sorted(kinds))}) in the clauses of {law.pred}")
    return kinds.pop()


def _variables(s: Skill) -> set[Var]:
    out = set(s.head.variables())
    for part in (s.percepts, s.start, s.requires, s.subgoals, s.actions):
        for x in part:
            out |= x.variables()
    return out


def _fresh(name: str, taken: set[str]) -> str:
    k, cand = 1, name
    while cand in taken:
        k += 1
        cand = f"{name}{k}"
    return cand


def _rebuild(program: Program, skills: list[Skill], goals: tuple[GoalSpec, ...]) -> Program:
    """``program`` with these skills (numbered afresh, as the checker numbers them) and goals."""
    numbered, by_pred = [], {}
    for n, s in enumerate(skills):
        group = by_pred.setdefault(s.head.pred, [])
        s = replace(s, index=len(group) + 1, number=n)
        group.append(s)
        numbered.append(s)
    return replace(program, skills=tuple(numbered), goals=goals,
                   skills_by_pred={k: tuple(v) for k, v in by_pred.items()})


__all__ = ["TransformError", "compile_laws", "drop_laws", "replace_law"]
