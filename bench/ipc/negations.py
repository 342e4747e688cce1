"""Negative preconditions and equality for the independent replay (strips.py).

pyperplan's parser reads neither ``(not (p ...))`` nor ``(= ?a ?b)`` in a precondition, and
many IPC domains use both. Before pyperplan parses a domain, each such literal of an action's
precondition is written as a positive atom of a predicate of its own (``(not (at ?t ?l))``
-> ``(replay-not-at ?t ?l)``, declared with ``at``'s parameters; ``(= ?a ?b)`` ->
``(replay-eq ?a ?b)``, ``(not (= ...))`` -> ``(replay-neq ...)``), and the replay tests those
atoms against the state instead of looking them up (``split``); a goal's negative literals
likewise. Anything else pyperplan does not read (``forall``, ``when``, ``or``) is left as it
is, for pyperplan to refuse.
"""

from __future__ import annotations

import re

NOT, EQ, NEQ = "replay-not-", "replay-eq", "replay-neq"

Tree = list | str


def _read(text: str) -> list[Tree]:
    """The s-expressions of ``text`` (comments dropped) as nested lists of tokens."""
    tokens = re.findall(r"\(|\)|[^\s()]+", re.sub(r";[^\n]*", "", text))
    stack: list[list[Tree]] = [[]]
    for tok in tokens:
        if tok == "(":
            stack.append([])
        elif tok == ")":
            if len(stack) == 1:
                raise ValueError("negations: unbalanced ')' in the domain")
            done = stack.pop()
            stack[-1].append(done)
        else:
            stack[-1].append(tok)
    if len(stack) != 1:
        raise ValueError("negations: unbalanced '(' in the domain")
    return stack[0]


def _write(tree: Tree) -> str:
    return tree if isinstance(tree, str) else "(" + " ".join(map(_write, tree)) + ")"


def _is(tree: Tree, head: str) -> bool:
    return isinstance(tree, list) and bool(tree) and str(tree[0]).lower() == head


def _positive(tree: Tree, used: set[str]) -> Tree:
    """``tree`` (a precondition) with its negative literals and equalities as atoms."""
    if not isinstance(tree, list):
        return tree
    if _is(tree, "not") and len(tree) == 2 and isinstance(tree[1], list) and tree[1]:
        inner = tree[1]
        if _is(inner, "="):
            used.add(NEQ)
            return [NEQ, *inner[1:]]
        if isinstance(inner[0], str) and not _is(inner, "and") and not _is(inner, "or"):
            used.add(inner[0].lower())
            return [NOT + inner[0].lower(), *inner[1:]]
    if _is(tree, "="):
        used.add(EQ)
        return [EQ, *tree[1:]]
    return [_positive(t, used) for t in tree]


def _declare(define: list, used: set[str]) -> bool:
    """Declare the predicates of ``used`` in ``define``'s ``:predicates``; False if it has
    none."""
    predicates = next((i for i in define if _is(i, ":predicates")), None)
    if predicates is None:
        return False
    declared = {str(d[0]).lower(): d[1:] for d in predicates[1:] if isinstance(d, list) and d}
    for name in sorted(used):
        if name in (EQ, NEQ):
            predicates.append([name, "?a", "?b"])
        elif name in declared:
            predicates.append([NOT + name, *declared[name]])
    return True


def positive(domain: str, problem: str = "") -> tuple[str, str]:
    """Domain and problem texts with the actions' preconditions' and the goal's negative
    literals and equalities as atoms of predicates declared for them; the texts themselves
    when they have none."""
    if re.search(r"\(\s*(not|=)[\s(]", domain + problem, re.I) is None:
        return domain, problem
    forms, goal_forms = _read(domain), _read(problem) if problem else []
    define = next((f for f in forms if _is(f, "define")), None)
    if define is None:
        return domain, problem
    used: set[str] = set()
    for item in define:
        if _is(item, ":action"):
            for k in range(len(item) - 1):
                if str(item[k]).lower() == ":precondition":
                    item[k + 1] = _positive(item[k + 1], used)
    goal_used: set[str] = set()
    for form in goal_forms:
        for k, item in enumerate(form if _is(form, "define") else ()):
            if _is(item, ":goal"):
                form[k] = [item[0], *(_positive(t, goal_used) for t in item[1:])]
    if not _declare(define, used | goal_used):
        return domain, problem
    new_problem = "\n".join(map(_write, goal_forms)) if goal_used else problem
    return "\n".join(map(_write, forms)), new_problem


def split(pre: tuple[tuple[str, ...], ...]) -> tuple[tuple, tuple, tuple, tuple]:
    """An operator's preconditions as (atoms that must hold, atoms that must not,
    pairs that must be equal, pairs that must differ)."""
    holds, absent, same, differ = [], [], [], []
    for atom in pre:
        if atom[0].startswith(NOT):
            absent.append((atom[0][len(NOT):], *atom[1:]))
        elif atom[0] == EQ:
            same.append(atom[1:])
        elif atom[0] == NEQ:
            differ.append(atom[1:])
        else:
            holds.append(atom)
    return tuple(holds), tuple(absent), tuple(same), tuple(differ)
