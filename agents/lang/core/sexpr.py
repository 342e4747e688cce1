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
    MAX_LIST_ITEMS,
    MAX_TEXT_CHARS,
    MAX_TOKEN_CHARS,
    number_problem,
    shorten,
)
from .terms import Var

_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*([eE][+-]?\d+)?|\.\d+([eE][+-]?\d+)?)$")


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
    at a list nested deeper than MAX_DEPTH, at an inner list longer than MAX_LIST_ITEMS, or
    after MAX_DIAGNOSTICS problems (the forms completed so far are returned, so that their
    own problems are reported too)."""
    if len(text) > MAX_TEXT_CHARS:
        return [], [Diagnostic(source, 1, 1, f"text of {len(text)} characters is longer than "
                                             f"the limit of {MAX_TEXT_CHARS}")]
    return _Reader(source).run(text)


# One lexeme: a newline, blanks, a comment, a parenthesis, or a token (anything else).
_LEXEME = re.compile(r"\n|[ \t\r]+|;[^\n]*|[()]|[^() \t\r\n;]+")


class _Reader:
    """The state of one ``read``: the open lists, the forms done, the diagnostics."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.diags: list[Diagnostic] = []
        self.forms: list = []
        self.stack: list[tuple[int, int, list]] = []  # (line, col, items) of open lists
        self.suspect: tuple[int, int] | None = None  # first '(' in column 1 inside a list

    def run(self, text: str) -> tuple[list, list[Diagnostic]]:
        line, line_start = 1, 0
        for match in _LEXEME.finditer(text):
            lexeme = match.group()
            first = lexeme[0]
            if first == "\n":
                line, line_start = line + 1, match.end()
                continue
            if first in " \t\r;":
                continue
            col = match.start() - line_start + 1
            if len(self.diags) >= MAX_DIAGNOSTICS:
                return self.stop(line, col, f"more than {MAX_DIAGNOSTICS} problems")
            if first == "(":
                if len(self.stack) >= MAX_DEPTH:
                    return self.stop(line, col, f"lists nested deeper than {MAX_DEPTH} levels")
                if col == 1 and self.stack and self.suspect is None:
                    self.suspect = (line, col)
                self.stack.append((line, col, []))
            elif first == ")":
                self.close(line, col)
            else:
                for node in _atoms(lexeme, line, col, self.source, self.diags):
                    self.add(node)
            if len(self.stack) > 1 and len(self.stack[-1][2]) > MAX_LIST_ITEMS:
                return self.stop(line, col, f"the list opened at {self.stack[-1][0]}:"
                                 f"{self.stack[-1][1]} has more than {MAX_LIST_ITEMS} items")
        if self.stack:
            self.unclosed()
        return self.forms, self.diags

    def add(self, node: object) -> None:
        (self.stack[-1][2] if self.stack else self.forms).append(node)

    def close(self, line: int, col: int) -> None:
        if not self.stack:
            self.diags.append(Diagnostic(self.source, line, col,
                                         "unexpected ')' with no list open"))
            return
        ol, oc, items = self.stack.pop()
        self.add(SList(tuple(items), ol, oc))

    def stop(self, line: int, col: int, why: str) -> tuple[list, list[Diagnostic]]:
        """Give up at line:col, keeping the forms completed so far."""
        self.diags.append(Diagnostic(self.source, line, col, f"{why}; reading stops here"))
        return self.forms, self.diags

    def unclosed(self) -> None:
        ol, oc, _ = self.stack[0]
        hint = ""
        if self.suspect is not None:
            hint = (f"; the form starting here seems to end before line {self.suspect[0]}, "
                    "where a new top-level form starts")
        self.diags.append(Diagnostic(self.source, ol, oc,
                                     f"'(' is never closed (missing ')'{hint})"))


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
