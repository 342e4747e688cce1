"""A program's goals, skills and concepts as a graph (`teleo graph PROGRAM`; as
py_trees renders a tree): the program's goals on top, each pointing to the skills that achieve
it, each nonprimitive skill to the skills of its :subgoals (an SCS body, seed 002, to its
steps, and a step that is a subgoal to that subgoal's skills); and, beside them, each concept
pointing to the concepts it is defined from (through a `not`: dashed). Primitive skills (with
:actions) and concepts read from percepts alone have kinds of their own, drawn apart.

A subgoal or goal that no skill achieves points to its concept (dashed): only inference can
make it true. Every node's detail (the SVG's tooltip) is the clause as read.
"""

from __future__ import annotations

from agents.lang import Literal, Program, Skill
from agents.lang.core.conjunction import Conjunction
from tools.records.drawing import Graph


def _conds(name: str, conds: tuple) -> str:
    return f"\n{name} " + " ".join(str(c) for c in conds) if conds else ""


def skill_detail(s: Skill) -> str:
    """One skill clause as text (its sections that are given)."""
    return (f"{s.name}: {s.head}" + _conds(":percepts", s.percepts) + _conds(":start", s.start)
            + _conds(":requires", s.requires) + _conds(":subgoals", s.subgoals)
            + _conds(":actions", s.actions) + ("\n:body " + str(s.body) if s.body else ""))


def _concept_id(pred: str) -> str:
    return f"concept:{pred}"


def _skill_id(s: Skill) -> str:
    return f"skill:{s.name}"


class _Builder:
    def __init__(self, program: Program, title: str) -> None:
        self.p, self.g = program, Graph(title)
        self.steps = 0

    def concept(self, pred: str) -> str:
        clauses = self.p.concepts.get(pred, ())
        kind = "percept-concept" if clauses and all(c.primitive for c in clauses) \
            else "concept"
        detail = "\n".join(f"{c.head} #{c.index}" + _conds(":percepts", c.percepts)
                           + _conds(":relations", c.relations) + _conds(":tests", c.tests)
                           for c in clauses) or f"{pred}: no clause (asserted or a percept)"
        return self.g.node(_concept_id(pred), pred, kind, detail)

    def skill(self, s: Skill) -> str:
        sid = _skill_id(s)
        if sid in self.g.nodes:
            return sid
        kind = "body" if s.body is not None else "primitive" if s.kind == "primitive" \
            else "skill"
        acts = " " + " ".join(str(a) for a in s.actions) if s.actions else ""
        self.g.node(sid, f"{s.head} #{s.index}{acts}", kind, skill_detail(s))
        for sub in s.subgoals:
            self.achieve(sid, sub, str(sub))
        if s.body is not None:
            self.g.edge(sid, self.step(s.body))
        return sid

    def achieve(self, src: str, goal: object, label: str) -> None:
        """Edges from ``src`` to what achieves ``goal`` (a literal or a conjunction)."""
        literals = goal.literals if isinstance(goal, Conjunction) else (goal,)
        for lit in literals:
            skills = self.p.skills_for(lit.pred)
            for s in skills:
                self.g.edge(src, self.skill(s), label)
            if not skills:
                self.g.edge(src, self.concept(lit.pred), f"{label} (no skill)", dashed=True)

    def step(self, node: object) -> str:
        """A node for one step of an SCS body (seed 002), with its children. Read by their
        fields (a construct's ``mods`` and ``steps``, a branch's ``conds`` and ``step``, a
        subgoal's ``literal``): only the registry imports a mechanism's own modules
        (tests/test_layering.py)."""
        self.steps += 1
        sid = f"step:{self.steps}"
        if hasattr(node, "mods") and hasattr(node, "steps"):   # do, do-first, repeat, ...
            self.g.node(sid, str(getattr(node, "name", "construct")), "step", str(node))
            for child in node.steps:
                inner = getattr(child, "step", child)           # a branch's step
                conds = getattr(child, "conds", None) if inner is not child else None
                label = "(" + " ".join(map(str, conds)) + ")" if conds else ""
                self.g.edge(sid, self.step(inner), label)
        elif isinstance(getattr(node, "literal", None), Literal):  # a subgoal
            self.g.node(sid, str(node.literal), "step", f"subgoal {node.literal}")
            self.achieve(sid, node.literal, "")
        else:                                                   # act, assert, wait, atomic
            self.g.node(sid, str(node), "step", str(node))
        return sid

    def build(self) -> Graph:
        for k, goal in enumerate(self.p.goals, 1):
            gid = self.g.node(f"goal:p{k}", str(goal.literal), "goal",
                              f"program goal p{k}: {goal.literal}")
            self.achieve(gid, goal.literal, "")
        for s in self.p.skills:  # skills no goal reaches (a user's goals reach them)
            self.skill(s)
        for pred in sorted(self.p.concepts):
            cid = self.concept(pred)
            for clause in self.p.concepts[pred]:
                for rel in clause.relations:
                    self.g.edge(cid, self.concept(rel.pred),
                                "not" if rel.negated else "", dashed=rel.negated)
        return self.g


def program_graph(program: Program, title: str = "") -> Graph:
    """The graph of ``program`` (see the module doc); ``title``: what it is called."""
    return _Builder(program, title or (program.sources[0] if program.sources else "program")
                    ).build()
