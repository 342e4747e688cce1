"""The pddl package's domain and problem objects turned into world/pddl/task.py's data, with the
checks the library leaves to its user: constructs outside the STRIPS fragment, and a problem
naming an object, type or predicate its domain does not declare."""

from __future__ import annotations

import re
from typing import Any

from world.errors import ConfigError
from world.pddl.task import ROOT_TYPE, DomainModel, Lit, Operator, Task, locate, uncommented
from world.pddl.type_list import ALIAS

_UNSUPPORTED = {
    "When": "conditional effects (when; :conditional-effects)",
    "Forall": "universal quantifiers (forall; :conditional-effects)",
    "ForallCondition": "universal quantifiers (forall; :universal-preconditions)",
    "ExistsCondition": "existential quantifiers (exists; :existential-preconditions)",
    "Or": "disjunctions (or; :disjunctive-preconditions)",
    "Imply": "implications (imply; :disjunctive-preconditions)",
    "OneOf": "non-deterministic effects (oneof; :non-deterministic)",
}


def domain_model(d: Any, path: str, text: str) -> DomainModel:
    """A DomainModel of the library's Domain ``d`` (read from ``text`` in ``path``)."""
    types = tuple(sorted((_type(t), _type(p) if p else ROOT_TYPE)
                         for t, p in d.types.items() if _type(t) != ROOT_TYPE))
    declared = {t for t, _ in types} | {ROOT_TYPE}
    constants = tuple(sorted((str(c.name).lower(), _one_type(c.type_tags, declared, path, text,
                                                             str(c.name)))
                             for c in d.constants))
    preds = tuple(sorted((str(p.name).lower(), _params(p.terms, declared, path, text))
                         for p in d.predicates))
    arity = {p: len(ps) for p, ps in preds}
    if "object" in arity:   # the type of the objects' percepts (perception.py)
        raise ConfigError(f"{locate(path, text, 'object', ':predicates')}: pddl: a predicate "
                          f"named 'object' is not supported: the world's object percepts "
                          f"are (object NAME type T)")
    ops = []
    low = uncommented(text).lower()
    for a in sorted(d.actions, key=lambda a: (_find(low, rf"\(\s*:action\s+"
                                                        rf"{re.escape(str(a.name).lower())}"
                                                        rf"(?![\w-])"), str(a.name))):
        name = str(a.name).lower()
        where = locate(path, text, name, after=":action")
        start = _find(low, rf"\(\s*:action\s+{re.escape(name)}(?![\w-])")
        params = _params(a.parameters, declared, path, text)
        known = {v for v, _ in params} | {c for c, _ in constants}
        pre = in_text_order(_literals(a.precondition, where, f"the precondition of {name}"),
                            low, _find(low, r":precondition\b", start))
        add, delete = [], []
        for lit in in_text_order(_literals(a.effect, where, f"the effect of {name}"), low,
                                 _find(low, r":effect\b", start)):
            if lit.pred == "=":
                raise ConfigError(f"{where}: pddl: action {name}: an effect cannot be an "
                                  f"equality: {lit.text()}")
            (delete if lit.negated else add).append(Lit(lit.pred, lit.args))
        for lit in [*pre, *add, *delete]:
            _check_lit(lit, arity, known, where, f"action {name}")
        ops.append(Operator(name, params, tuple(pre), tuple(add), tuple(delete)))
    return DomainModel(str(d.name).lower(), types, constants, preds, tuple(ops), path)


def task_of(model: DomainModel, p: Any, path: str, text: str) -> Task:
    """A Task of the library's Problem ``p`` for ``model``, every name checked against it."""
    if p.domain_name is not None and str(p.domain_name).lower() != model.name:
        raise ConfigError(f"{locate(path, text, str(p.domain_name), ':domain')}: pddl: the "
                          f"problem is for domain {str(p.domain_name).lower()!r}, not "
                          f"{model.name!r} ({model.path})")
    declared = {t for t, _ in model.types} | {ROOT_TYPE}
    objects = dict(model.constants)
    for o in p.objects:
        name = str(o.name).lower()
        objects[name] = _one_type(o.type_tags, declared, path, text, str(o.name))
    arity = {q: len(ps) for q, ps in model.predicates}
    init = set()
    for f in p.init:
        lit = _literal(f, path, "the initial state")
        if lit.negated or lit.pred == "=":
            raise ConfigError(f"{path}: pddl: the initial state holds atoms only, got "
                              f"{lit.text()}")
        _check_lit(lit, arity, set(objects), path, "the initial state", text, ":init")
        init.add((lit.pred, *lit.args))
    goal = _literals(p.goal, path, "the goal") if p.goal is not None else []
    low = uncommented(text).lower()
    goal = in_text_order(goal, low, _find(low, r"\(\s*:goal\b"))
    for lit in goal:
        _check_lit(lit, arity, set(objects), path, "the goal", text, ":goal")
    return Task(model, str(p.name).lower(), tuple(sorted(objects.items())), frozenset(init),
                tuple(goal), path)


def _find(text: str, pattern: str, start: int = 0) -> int:
    """Where ``pattern`` first matches in ``text`` from ``start`` (len(text) if nowhere)."""
    m = re.compile(pattern).search(text, start if start < len(text) else 0)
    return m.start() if m else len(text)


def in_text_order(lits: list[Lit], text: str, start: int) -> list[Lit]:
    """``lits`` in the order they are written in ``text`` (lower-case) from ``start``: the
    library keeps a conjunction as a set, whose order changes from one process to the next,
    and the order of a skill's conditions and of a goal's conjuncts matters to the solver."""
    def key(lit: Lit) -> tuple[int, str]:
        body = r"\s+".join(re.escape(x) for x in (lit.pred, *lit.args))
        return _find(text, rf"\(\s*{body}\s*\)", start), lit.text()

    return sorted(lits, key=key)


def _one_type(tags, declared: set[str], path: str, text: str, name: str) -> str:
    tags = sorted({_type(t) for t in tags}) or [ROOT_TYPE]
    if len(tags) > 1:
        raise ConfigError(f"{locate(path, text, name)}: pddl: object {name.lower()} has "
                          f"several types ({' '.join(tags)}); an object has one")
    if tags[0] not in declared:
        raise ConfigError(f"{locate(path, text, name)}: pddl: object {name.lower()} is of "
                          f"the undeclared type {tags[0]!r} (declared: "
                          f"{', '.join(sorted(declared))})")
    return tags[0]


def _params(terms, declared: set[str], path: str, text: str
            ) -> tuple[tuple[str, tuple[str, ...]], ...]:
    out = []
    for t in terms:
        tags = tuple(sorted({_type(x) for x in t.type_tags})) or (ROOT_TYPE,)
        for tag in tags:
            if tag not in declared:
                raise ConfigError(f"{locate(path, text, tag)}: pddl: ?{str(t.name).lower()} "
                                  f"is of the undeclared type {tag!r}")
        out.append((f"?{str(t.name).lower()}", tags))
    return tuple(out)


def _type(name: Any) -> str:
    """A type's name, lower-cased; the root's alias (type_list.py) read as the root."""
    low = str(name).lower()
    return ROOT_TYPE if low == ALIAS else low


def _literals(formula: Any, where: str, what: str) -> list[Lit]:
    """The conjuncts of ``formula``: atoms, negated atoms, (in)equalities."""
    if formula is None:
        return []
    kind = type(formula).__name__
    if kind == "And":
        return [lit for op in formula.operands for lit in _literals(op, where, what)]
    return [_literal(formula, where, what)]


def _literal(f: Any, where: str, what: str) -> Lit:
    kind = type(f).__name__
    if kind == "Not":
        inner = _literal(f.argument, where, what)
        if inner.negated:
            return Lit(inner.pred, inner.args)
        return Lit(inner.pred, inner.args, True)
    if kind == "Predicate":
        return Lit(str(f.name).lower(), tuple(_term(t) for t in f.terms))
    if kind == "EqualTo":
        return Lit("=", (_term(f.left), _term(f.right)))
    name = _UNSUPPORTED.get(kind)
    if name is None:
        name = "numeric fluents" if kind in ("Increase", "Decrease", "Assign", "ScaleUp",
                                             "ScaleDown", "NumericFunction") else kind
    raise ConfigError(f"{where}: pddl: {what}: {name} not supported; the pddl world runs "
                      f"STRIPS conjunctions of literals")


def _term(t: Any) -> str:
    name = str(t.name).lower()
    return f"?{name}" if type(t).__name__ == "Variable" else name


def _check_lit(lit: Lit, arity: dict[str, int], known: set[str], where: str, what: str,
               text: str = "", after: str = "") -> None:
    at = (lambda n: locate(where, text, n, after)) if text else (lambda n: where)
    if lit.pred != "=":
        if lit.pred not in arity:
            raise ConfigError(f"{at(lit.pred)}: pddl: {what}: undeclared predicate "
                              f"{lit.pred!r} in {lit.text()}")
        if arity[lit.pred] != len(lit.args):
            raise ConfigError(f"{at(lit.pred)}: pddl: {what}: {lit.text()}: {lit.pred} takes "
                              f"{arity[lit.pred]} argument(s), got {len(lit.args)}")
    for a in lit.args:
        if a not in known:
            kind = "variable" if a.startswith("?") else "object"
            raise ConfigError(f"{at(a)}: pddl: {what}: undeclared {kind} {a!r} in "
                              f"{lit.text()}")
