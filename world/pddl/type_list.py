"""The root type ``object`` written out in a domain, blanked for the parser, positions kept.

Two IPC habits the `pddl` package refuses are harmless: a type declared twice, once under
``object`` and once under another type (storage's ``area - object`` and ``area - surface``;
every type is below the root anyway), and ``- object`` closing a list of parameters or
constants (the library knows no type of that name; untyped names at a list's end are of the
root type). Each is blanked out before parsing, the text keeping its length so that every
later message names the same line and column. A type declared under two types other than the
root is left for the parser to refuse.

Two more (IPC tidybot) need a name for the root: ``object`` declared as a type (``(:types
robot cart object ...)``, a keyword to the library), and ``- object`` before other typed names
of a list (``?o - object ?c - cart``), which cannot be blanked (?o would become a cart).
``root_alias`` writes ``ALIAS``, a name of the same length, in both places, declared as a
type where ``object`` was (or, where it was not, added at the end of the type list: only what
follows the list on its own line moves); convert.py reads ``ALIAS`` back as the root type, so
``?o - object`` admits every object, as PDDL says. A domain that already names ``ALIAS``
is left as it is.
"""

from __future__ import annotations

import re

from world.pddl.costs import form_end
from world.pddl.task import ROOT_TYPE

_TYPES = re.compile(r"\(\s*:types\b", re.I)
_TOKEN = re.compile(r"[^\s()]+")
_UNDER_ROOT = re.compile(rf"(?<![\w-])-\s+{ROOT_TYPE}(?=\s*\))", re.I)
_ROOT_BEFORE = re.compile(rf"(?<![\w?-])-\s+({ROOT_TYPE})(?![\w-])(?=\s*[^\s)])", re.I)
_NAME = re.compile(rf"(?<![\w?-])({ROOT_TYPE})(?![\w-])", re.I)
ALIAS = "t-root"
"""The root type's name for the parser where ``object`` is written as a type (same length)."""


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
        code = code[:start] + _blanked(code[start:stop]) + code[stop:]
    end = form_end(code, m.start())   # in the type list a group's "- object" stays: the
    return _untyped(code[:m.start()]) + code[m.start():end] + _untyped(code[end:])  # last
                                                                # group alone has no parent


def _untyped(code: str) -> str:
    return _UNDER_ROOT.sub(lambda u: _blanked(u.group()), code)


def _blanked(text: str) -> str:
    """``text`` as blanks, its line breaks kept (``- \\n object``)."""
    return re.sub(r"[^\n]", " ", text)


def root_alias(code: str) -> str:
    """``code`` (a domain, after ``single_types``) with ``object`` declared as a type, and
    ``- object`` before other typed names outside the type list, written ``ALIAS``."""
    m = _TYPES.search(code)
    if m is None or re.search(rf"(?<![\w?-]){ALIAS}(?![\w-])", code, re.I):
        return code
    end = form_end(code, m.start())
    tokens = [(t.group().lower(), m.end() + t.start())
              for t in _TOKEN.finditer(code[m.end():end - 1])]
    declared = [at for k, (name, at) in enumerate(tokens)
                if name == ROOT_TYPE and (k == 0 or tokens[k - 1][0] != "-")]
    spans = [u.start(1) for u in _ROOT_BEFORE.finditer(code) if not m.start() <= u.start() < end]
    if not declared and not spans:
        return code
    for at in declared + spans:
        code = code[:at] + ALIAS + code[at + len(ALIAS):]
    if not declared:   # declared after the list's last name, under the root
        code = code[:end - 1] + " " + ALIAS + code[end - 1:]
    return code
