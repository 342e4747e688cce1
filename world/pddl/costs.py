"""Action costs (`:action-costs`, IPC 2008 on): run, with the costs ignored.

Many STRIPS domains of the IPC since 2008 (elevators, openstacks, parcprinter, pegsol,
scanalyzer, sokoban, transport, woodworking) declare `:action-costs`: a `(:functions
(total-cost) ...)` block, effects `(increase (total-cost) N)` or `(increase (total-cost)
(road-length ?a ?b))`, initial values `(= (road-length a b) 10)` and a `(:metric minimize
(total-cost))`. None of these changes which actions apply or what they do, so the world runs
such a domain with every cost construct blanked out of the text (same length, so that
file:line:col of any later error stays right) and says so (``NOTE``): its plans are executed
without their costs and not cost-optimal. Any other numeric construct left (a comparison in a
precondition, a change to a fluent other than total-cost) is refused as numeric fluents.
"""

from __future__ import annotations

import re
from pathlib import Path

from world.errors import ConfigError
from world.pddl.task import position

NOTE = ("action costs (:action-costs) are ignored: the plan is executed without its costs, "
        "its total cost is neither tracked nor minimised")
_DECLARED = re.compile(r"\(\s*:requirements\b[^)]*:action-costs\b", re.I)
_NUMERIC = re.compile(r"\(\s*(increase|decrease|assign|scale-up|scale-down|<=|>=|<|>"
                      r"|=\s*\()", re.I)


def declares_costs(code: str) -> bool:
    """Whether ``code`` (comments blanked) declares the `:action-costs` requirement, or uses
    action costs without it (a `:functions` block of `(total-cost)` alone, as some IPC files
    do)."""
    if _DECLARED.search(code) is not None:
        return True
    m = re.search(r"\(\s*:functions\b", code, re.I)
    if m is None:
        return False
    body = code[m.end():form_end(code, m.start()) - 1]
    return [n.lower() for n in re.findall(r"\(\s*([^\s()]+)", body)] == ["total-cost"]


def form_end(code: str, start: int) -> int:
    """The index just after the parenthesised expression opening at ``start``."""
    depth = 0
    for k in range(start, len(code)):
        if code[k] == "(":
            depth += 1
        elif code[k] == ")":
            depth -= 1
            if depth == 0:
                return k + 1
    return len(code)


def _blank(code: str, spans: list[tuple[int, int]], empty: list[tuple[int, int]]) -> str:
    """``code`` with each of ``spans`` blanked, and each of ``empty`` made ``(and)`` (an
    effect of its own: `:effect (increase (total-cost) 1)`), newlines kept."""
    chars = list(code)
    for a, b in [*spans, *empty]:
        for k in range(a, b):
            if chars[k] != "\n":
                chars[k] = " "
    for a, _ in empty:
        chars[a:a + 5] = list("(and)")
    return "".join(chars)


def _spans(code: str, pattern: str) -> list[tuple[int, int]]:
    return [(m.start(), form_end(code, m.start())) for m in re.finditer(pattern, code, re.I)]


def without_costs(code: str, path: str | Path, problem: bool) -> str:
    """``code`` (comments blanked) with the requirement and every cost construct blanked out;
    ConfigError naming the place of any numeric construct left."""
    spans = [(m.start(), m.end()) for m in re.finditer(r":action-costs\b", code, re.I)]
    empty: list[tuple[int, int]] = []
    if problem:
        spans += _spans(code, r"\(\s*:metric\b")
        spans += _spans(code, r"\(\s*=\s*\(")   # (= (road-length a b) 10) in :init
    else:
        spans += _spans(code, r"\(\s*:functions\b")
        for a, b in _spans(code, r"\(\s*increase\s+\(\s*total-cost\s*\)"):
            alone = re.search(r":effect\s*$", code[:a], re.I) is not None
            (empty if alone else spans).append((a, b))
    out = _blank(code, spans, empty)
    m = _NUMERIC.search(out)
    if m is not None:
        raise ConfigError(f"{position(path, code, m.start())}: pddl: numeric fluents "
                          f"({' '.join(m.group(1).split())}) not supported; of numbers the "
                          f"pddl world takes only action costs, which it ignores")
    return out
