"""S-expression reader that keeps line:col for every node (for file:line:col diagnostics).

Atoms: numbers (int/float), variables ``?x``, symbols (case kept: ``ME``, ``*gas``, ``:percepts``).
``;`` starts a comment to the end of the line. Seed 000, Table 6 writes ``?self?ad``: the reader
splits such a token into two variables and emits a warning (documented in docs/language.md).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass

from .errors import Diagnostic
from .limits import (
    MAX_DEPTH,
    MAX_DIAGNOSTICS,
    MAX_TEXT_CHARS,
    MAX_TOKEN_CHARS,
    number_problem,
    shorten,
)
from .terms import Var

_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*([eE][+-]?\d+)?|\.\d+([eE][+-]?\d+)?)$")
_DELIMS = set("() \t\r\n;")


@dataclass(frozen=True, slots=True)
class Atom:
    """A number, symbol (str) or Var, with its position."""

    value: object
    line: int
    col: int


@dataclass(frozen=True, slots=True)
class SList:
    """A parenthesised list of nodes, positioned at its opening parenthesis."""

    items: tuple
    line: int
    col: int


def atom_value(token: str) -> object:
    """Convert one token to int, float, Var or symbol str."""
    if _NUMBER.match(token):
        if any(c in token for c in ".eE"):
            return float(token)
        return int(token)
    if token.startswith("?") and len(token) > 1:
        return Var(token[1:])
    return token


def read(text: str, source: str = "<text>") -> tuple[list, list[Diagnostic]]:
    """Read every top-level form of ``text``; return (forms, diagnostics). Never raises.

    Within the bounds of limits.py: a text over MAX_TEXT_CHARS is not read, and reading stops
    at a list nested deeper than MAX_DEPTH or after MAX_DIAGNOSTICS problems (the forms
    completed so far are returned, so their own problems are reported too)."""
    if len(text) > MAX_TEXT_CHARS:
        return [], [Diagnostic(source, 1, 1, f"text of {len(text)} characters is longer than "
                                             f"the limit of {MAX_TEXT_CHARS}")]
    diags: list[Diagnostic] = []
    forms: list = []
    stack: list[tuple[int, int, list]] = []  # (line, col, items) of open lists
    line, col, i, n = 1, 1, 0, len(text)
    suspect = None  # first '(' in column 1 inside an open list: where a ')' is likely missing
    while i < n:
        if len(diags) >= MAX_DIAGNOSTICS:
            diags.append(Diagnostic(source, line, col, f"more than {MAX_DIAGNOSTICS} problems; "
                                    "reading stops here"))
            return forms, diags
        c = text[i]
        if c == "\n":
            line, col, i = line + 1, 1, i + 1
            continue
        if c in " \t\r":
            i, col = i + 1, col + 1
            continue
        if c == ";":
            while i < n and text[i] != "\n":
                i += 1
            continue
        if c == "(":
            if len(stack) >= MAX_DEPTH:
                diags.append(Diagnostic(source, line, col, f"lists nested deeper than {MAX_DEPTH}"
                                        " levels; reading stops here"))
                return forms, diags
            if col == 1 and stack and suspect is None:
                suspect = (line, col)
            stack.append((line, col, []))
            i, col = i + 1, col + 1
            continue
        if c == ")":
            if not stack:
                diags.append(Diagnostic(source, line, col, "unexpected ')' with no list open"))
            else:
                ol, oc, items = stack.pop()
                node = SList(tuple(items), ol, oc)
                (stack[-1][2] if stack else forms).append(node)
            i, col = i + 1, col + 1
            continue
        start, scol = i, col
        while i < n and text[i] not in _DELIMS:
            i += 1
        col += i - start
        token = text[start:i]
        for node in _atoms(token, line, scol, source, diags):
            (stack[-1][2] if stack else forms).append(node)
    if stack:
        ol, oc, _ = stack[0]
        hint = ""
        if suspect is not None:
            hint = (f"; the form starting here seems to end before line {suspect[0]}, where a "
                    "new top-level form starts")
        diags.append(Diagnostic(source, ol, oc, f"'(' is never closed (missing ')'{hint})"))
    return forms, diags


def _atoms(token: str, line: int, col: int, source: str, diags: list[Diagnostic]) -> list[Atom]:
    """Atoms of one token; ``?a?b`` becomes two variables with a warning (seed 000, Table 6).
    A token over MAX_TOKEN_CHARS or a number out of range gives an error and a stand-in atom
    (its first characters, or 0), so that the error is not followed by others it caused."""
    if len(token) > MAX_TOKEN_CHARS:
        diags.append(Diagnostic(source, line, col, f"token {shorten(token)} is longer than "
                                f"{MAX_TOKEN_CHARS} characters"))
        return [Atom(atom_value(token[:MAX_TOKEN_CHARS]), line, col)]
    if '"' in token or "'" in token or "`" in token:
        diags.append(Diagnostic(source, line, col, f"unexpected quote character in {token!r}; "
                                "strings are not part of the language, write a symbol"))
        return []
    if token.startswith("?") and token.count("?") > 1 and "??" not in token:
        parts = ["?" + p for p in token.split("?")[1:]]
        if all(len(p) > 1 for p in parts):
            diags.append(Diagnostic(source, line, col, f"{token!r} read as {len(parts)} variables "
                                    f"{' '.join(parts)} (missing space?)", "warning"))
            out, c = [], col
            for p in parts:
                out.append(Atom(atom_value(p), line, c))
                c += len(p)
            return out
    if token == "?":
        diags.append(Diagnostic(source, line, col, "'?' alone is not a variable; write ?name"))
        return []
    value = atom_value(token)
    problem = number_problem(value) if isinstance(value, (int, float)) else ""
    if problem:
        diags.append(Diagnostic(source, line, col, f"{shorten(token)}: {problem}"))
        return [Atom(0, line, col)]
    return [Atom(value, line, col)]


def to_text(node: object, width: int = 200) -> str:
    """Render a node back to s-expression text for a message, cut after ``width`` characters
    (a form can be as long as the file)."""
    parts: list[str] = []
    size = 0
    for piece in _pieces(node):
        parts.append(piece)
        size += len(piece)
        if size > width:
            return "".join(parts)[:width] + " ..."
    return "".join(parts)


def _pieces(node: object) -> Iterator[str]:
    if isinstance(node, SList):
        yield "("
        for k, item in enumerate(node.items):
            if k:
                yield " "
            yield from _pieces(item)
        yield ")"
    else:
        yield fmt_value(node.value if isinstance(node, Atom) else node)


def fmt_value(v: object) -> str:
    """Text of a constant or Var: ``ME``, ``20.0``, ``?x``."""
    if isinstance(v, Var):
        return "?" + v.name
    return str(v)
