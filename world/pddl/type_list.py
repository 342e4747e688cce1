"""The root type ``object`` written out in a domain, blanked for the parser, positions kept.

Two IPC habits the `pddl` package refuses are harmless: a type declared twice, once under
``object`` and once under another type (storage's ``area - object`` and ``area - surface``;
every type is below the root anyway), and ``- object`` closing a list of parameters or
constants (the library knows no type of that name; untyped names at a list's end are of the
root type). Each is blanked out before parsing, the text keeping its length so that every
later message names the same line and column. ``- object`` before other typed names of a
list, and a type declared under two types other than the root, are left for the parser to
refuse.
"""

from __future__ import annotations

import re

from world.pddl.costs import form_end
from world.pddl.task import ROOT_TYPE

_TYPES = re.compile(r"\(\s*:types\b", re.I)
_TOKEN = re.compile(r"[^\s()]+")
_UNDER_ROOT = re.compile(rf"(?<![\w-])-\s+{ROOT_TYPE}(?=\s*\))", re.I)


Group = tuple[list[tuple[str, int]], str, tuple[int, int]]
"""A group of the list: [(type name, position)], their parent (ROOT_TYPE for the last
group's names, which have none written), and the span of ``- parent`` ((0, 0) if none)."""


def _groups(body: str, offset: int) -> list[Group]:
    out: list[Group] = []
    names: list[tuple[str, int]] = []
    tokens = [(m.group().lower(), offset + m.start()) for m in _TOKEN.finditer(body)]
    k = 0
    while k < len(tokens):
        if tokens[k][0] == "-" and k + 1 < len(tokens):
            parent, at = tokens[k + 1]
            out.append((names, parent, (tokens[k][1], at + len(parent))))
            names, k = [], k + 2
        else:
            names.append(tokens[k])
            k += 1
    if names:
        out.append((names, ROOT_TYPE, (0, 0)))
    return out


def single_types(code: str) -> str:
    """``code`` (a domain, comments blanked) with a second declaration of a type under the
    root, and ``- object`` closing a list outside the type list, blanked out."""
    m = _TYPES.search(code)
    if m is None:
        return _untyped(code)
    groups = _groups(code[m.end():form_end(code, m.start()) - 1], m.end())
    parents: dict[str, list[str]] = {}
    for names, parent, _ in groups:
        for name, _ in names:
            parents.setdefault(name, []).append(parent)
    blank: list[tuple[int, int]] = []
    for names, parent, dash in groups:
        gone = 0
        for name, at in names:
            again = len(parents[name]) > 1 and any(p != ROOT_TYPE for p in parents[name])
            if parent == ROOT_TYPE and again:
                blank.append((at, at + len(name)))
                parents[name].remove(ROOT_TYPE)
                gone += 1
        if gone == len(names) and dash != (0, 0):
            blank.append(dash)
    for start, stop in blank:
        code = code[:start] + " " * (stop - start) + code[stop:]
    end = form_end(code, m.start())   # in the type list a group's "- object" stays: the
    return _untyped(code[:m.start()]) + code[m.start():end] + _untyped(code[end:])  # last
                                                                # group alone has no parent


def _untyped(code: str) -> str:
    return _UNDER_ROOT.sub(lambda u: " " * len(u.group()), code)
