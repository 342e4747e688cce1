"""The readers' bounds (docs/language.md, "Limits") and a bounded JSON reader.

Every text teleo reads (a program, a percept file, a goal, a world event) is read within these
bounds, so any input, however hostile, ends in a diagnostic naming file:line:col and never in
a Python exception (RecursionError, the 4300-digit ValueError) or a NaN let through.
"""

from __future__ import annotations

import json
import math
import re

from .errors import Diagnostic, ProgramError

MAX_TEXT_CHARS = 1024 * 1024
"""[characters] of one program or percept text, and [bytes] of such a file (the driving
program has 9,364)."""
MAX_DEPTH = 64
"""[levels] of nested lists in an s-expression or of arrays/objects in JSON. Programs use ~8;
64 keeps every recursive walk of a form (checks, compiled tests) far from Python's limit."""
MAX_LIST_ITEMS = 256
"""Items of one inner list (a clause, a literal, a percept: any list inside another list);
a top-level list (a section, Table 3's list of percepts) may hold any number."""
MAX_TOKEN_CHARS = 256
"""[characters] of one symbol, variable or number, and of one JSON string."""
INT_MIN, INT_MAX = -(2**63), 2**63 - 1
"""Integers are signed 64-bit: what msgpack carries on the bus."""
MAX_DIAGNOSTICS = 100
"""Errors reported per source; reading stops after the first MAX_DIAGNOSTICS."""
MAX_GOAL_CHARS = 64 * 1024
"""[characters] of one goal's text, e.g. ``(package-delivered PACKET2)`` has 27; a
conjunction of the 29 (on X Y) literals of a 30-block tower, about 400; a PDDL problem's goal
of a few hundred literals (every cell of a grid to visit), some 5,000 to 40,000."""
MAX_EVENT_CHARS = 64 * 1024
"""[characters] of one world event's JSON text."""
MAX_STATE_CHARS = 64 * 1024 * 1024
"""[bytes] of an engine state file (``teleo step --save-state``): learned skills, goal
stacks and loop watches grow with a run."""
MAX_STATE_STRING = 1024 * 1024
"""[characters] of one string in an engine state file: a failure reason naming the whole
chain of subgoals tried, a learned skill clause, a conjunctive goal (MAX_GOAL_CHARS)."""


def number_problem(value: int | float) -> str:
    """Why a number read from text cannot be a value ("" when it can): integers must fit in
    64 bits and floats must be finite (no NaN or infinity)."""
    if isinstance(value, int):
        if not INT_MIN <= value <= INT_MAX:
            return "integer out of range (integers are signed 64-bit)"
        return ""
    if not math.isfinite(value):
        return f"number {value} is not finite (NaN and infinity are not values)"
    return ""


def position(text: str, index: int) -> tuple[int, int]:
    """(line, col), 1-based, of character ``index`` of ``text``."""
    line = text.count("\n", 0, index) + 1
    return line, index - text.rfind("\n", 0, index)


def shorten(text: str, width: int = 40) -> str:
    """``text`` cut to ``width`` characters for a message, with the full length said."""
    return text if len(text) <= width else f"{text[:width]}... ({len(text)} characters)"


# JSON tokens that need a bound checked before json.loads sees them: strings (with their
# escapes), brackets, numbers, and the non-standard NaN/Infinity that json.loads accepts.
_JSON_TOKEN = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"?|[\[\]{}]|-?Infinity|NaN'
                         r"|-?\d+(?:\.\d*)?(?:[eE][+-]?\d*)?", re.DOTALL)
_OPEN, _CLOSE = frozenset("[{"), frozenset("]}")


def read_json(text: str, source: str, max_chars: int = MAX_TEXT_CHARS,
              max_string: int = MAX_TOKEN_CHARS) -> object:
    """Parse JSON ``text`` within the bounds above (strings of at most ``max_string``
    characters as written); raises ProgramError naming source:line:col (too long, too deep,
    a number out of range, NaN/Infinity, a string too long, bad JSON)."""
    if len(text) > max_chars:
        raise ProgramError([Diagnostic(source, 1, 1, f"text of {len(text)} characters is longer "
                                                     f"than the limit of {max_chars}")])
    problem = _json_bounds(text, max_string)
    if problem is not None:
        index, message = problem
        raise ProgramError([Diagnostic(source, *position(text, index), message)])
    try:
        return json.loads(text, parse_constant=_no_constant)
    except json.JSONDecodeError as exc:
        raise ProgramError([Diagnostic(source, exc.lineno, exc.colno, f"bad JSON: {exc.msg}")]) \
            from None
    except ValueError as exc:  # from _no_constant, should _json_bounds ever miss one
        raise ProgramError([Diagnostic(source, 1, 1, f"bad JSON: {exc}")]) from None


def _json_bounds(text: str, max_string: int) -> tuple[int, str] | None:
    """(index, what is wrong) for the first token over a bound, or None."""
    depth = 0
    for match in _JSON_TOKEN.finditer(text):
        token = match.group()
        first = token[0]
        if first in _OPEN:
            depth += 1
            if depth > MAX_DEPTH:
                return match.start(), f"nested deeper than {MAX_DEPTH} levels"
        elif first in _CLOSE:
            depth -= 1
        elif first == '"':
            problem = _string_problem(token, max_string)
            if problem:
                return match.start(), problem
        elif token in ("NaN", "Infinity", "-Infinity"):
            return match.start(), f"{token} is not a number teleo accepts (values are finite)"
        else:
            problem = _json_number_problem(token)
            if problem:
                return match.start(), problem
    return None


def _string_problem(token: str, max_string: int) -> str:
    if len(token) - 2 > max_string:
        return f"string of {len(token) - 2} characters is longer than {max_string}"
    if "\\u" in token and token.endswith('"') and len(token) > 1:
        try:
            json.loads(token).encode("utf-8")
        except (ValueError, UnicodeEncodeError):
            return f"string {shorten(token)} holds an escape that is not a character"
    return ""


def _json_number_problem(token: str) -> str:
    if len(token) > MAX_TOKEN_CHARS:
        return f"number of {len(token)} characters is longer than {MAX_TOKEN_CHARS}"
    try:
        value = float(token) if any(c in token for c in ".eE") else int(token)
    except ValueError:
        return ""  # not a number json accepts either: json.loads says where
    problem = number_problem(value)
    return f"{shorten(token)}: {problem}" if problem else ""


def _no_constant(name: str) -> object:
    raise ValueError(f"{name} is not a value")  # unreachable: _json_bounds refuses them first
