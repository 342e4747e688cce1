"""Loading programs and percepts from text; ``read_text`` is the only function touching files.
Part of the assembly (docs/architecture.md): a program is read with the registered mechanisms
(agents/lang/registry.py) unless told others."""

from __future__ import annotations

import codecs
from pathlib import Path

from .core.errors import Diagnostic, LangError, ProgramError
from .core.limits import MAX_DIAGNOSTICS, MAX_TEXT_CHARS, read_json, shorten
from .core.program import Program
from .core.sexpr import Atom, SList, read, to_text
from .core.terms import Percept, is_const
from .reading.checks import build_program
from .reading.parser import Parts, parse_forms
from .registry import MECHANISMS


def read_text(path: str | Path, limit: int = MAX_TEXT_CHARS) -> str:
    """Contents of ``path``; raises ProgramError naming the file if it cannot be read, is over
    ``limit`` bytes, or is not UTF-8 (``decode_text``)."""
    try:
        with open(path, "rb") as f:
            data = f.read(limit + 1)
    except OSError as exc:
        raise ProgramError([Diagnostic(str(path), 0, 0, f"cannot read file: {exc.strerror}")]) \
            from None
    return decode_text(data, str(path), limit)


def decode_text(data: bytes, source: str, limit: int = MAX_TEXT_CHARS) -> str:
    """``data`` as UTF-8 text (a leading byte-order mark skipped); raises ProgramError when it
    is over ``limit`` bytes or holds a byte that is not UTF-8 (with that byte's line:col)."""
    if len(data) > limit:
        raise ProgramError([Diagnostic(source, 0, 0, f"file is larger than the limit of "
                                                     f"{limit} bytes")])
    if data.startswith(codecs.BOM_UTF8):
        data = data[len(codecs.BOM_UTF8):]
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ProgramError([_not_utf8(source, data, exc)]) from None


def _not_utf8(source: str, data: bytes, exc: UnicodeDecodeError) -> Diagnostic:
    """Where the first byte that is not UTF-8 is, as line:col (col counts characters)."""
    start = data.rfind(b"\n", 0, exc.start) + 1
    line = data.count(b"\n", 0, exc.start) + 1
    col = len(data[start:exc.start].decode("utf-8", errors="replace")) + 1
    return Diagnostic(source, line, col, f"not UTF-8: byte 0x{data[exc.start]:02x} "
                      f"({exc.reason}); save the file as UTF-8")


EMPTY_PROGRAM = ("the file holds no forms (an empty program): expected (concepts ...), "
                 "(skills ...) or (goals ...)")
EMPTY_FILE = "the file holds no forms (the program's other files do)"


def load_program_text(text: str, source: str = "<text>", *more: tuple[str, str],
                      mechanisms: tuple = MECHANISMS) -> Program:
    """Parse and check program ``text`` (plus further (text, source) pairs forming one
    program) with ``mechanisms`` (agents/lang/core/mechanism.py). A program whose files hold no
    forms at all is an error; one empty file among others is a warning."""
    parts = Parts(mechanisms)
    sources = ((text, source), *more)
    read_all = [(read(t, src), src) for t, src in sources]
    empty = not any(forms for (forms, _), _ in read_all)
    for (forms, diags), src in read_all:
        if not forms and not diags:  # all empty: a run would "complete" with 0 of 0 goals
            diags.append(Diagnostic(src, 1, 1, EMPTY_PROGRAM if empty else EMPTY_FILE,
                                    "error" if empty else "warning"))
        parts.diags.extend(diags)
        parts.sources.append(src)
        parse_forms(forms, src, parts)
    return build_program(parts)


def load_program(path: str | Path, *more: str | Path, mechanisms: tuple = MECHANISMS) -> Program:
    """Load a program file; further files are read into the same program (e.g. a table of skills
    plus the concepts it uses). Raises ProgramError with every diagnostic."""
    texts = [(read_text(p), str(p)) for p in (path, *more)]
    return load_program_text(texts[0][0], texts[0][1], *texts[1:], mechanisms=mechanisms)


def parse_percepts(text: str, source: str = "<percepts>") -> tuple[Percept, ...]:
    """Percepts from text: the seed's Table 3 form ``((street B) (self ME speed 20.0) ...)``,
    a sequence of ``(type id attr value ...)`` forms, or JSON
    neutral lists ``[["street", "B"], ...]``.
    Raises ProgramError with every problem found."""
    if text.lstrip().startswith(("[", "{")):
        return _json_percepts(text, source)
    forms, diags = read(text, source)
    nodes = []
    for f in forms:
        if isinstance(f, SList) and f.items and all(isinstance(x, SList) for x in f.items):
            nodes.extend(f.items)
        else:
            nodes.append(f)
    out = []
    for n in nodes:
        if len(diags) > MAX_DIAGNOSTICS:
            break
        p = _percept(n, source, diags)
        if p is not None:
            out.append(p)
    if any(d.severity == "error" for d in diags):
        raise ProgramError(diags)
    return tuple(out)


def percept_list(data: object, source: str) -> list:
    """The percepts in a JSON document, in one of the forms a percept file may take
    (docs/language.md, "Percept files"): a list of percepts; an object whose "percepts" is
    that list (a Percepts message as `teleo explain --percepts` or a script writes it); or a
    saved `teleo echo` line, an object whose "msg" is a Percepts message. Anything else
    raises ProgramError saying which forms are accepted."""
    if isinstance(data, list):
        return data
    if isinstance(data, dict) and isinstance(data.get("msg"), dict) and "percepts" in data["msg"]:
        data = data["msg"]
    if isinstance(data, dict) and isinstance(data.get("percepts"), list):
        return data["percepts"]
    got = (f"an object with keys {', '.join(sorted(map(str, data)))[:120] or '(none)'}"
           if isinstance(data, dict) else f"a JSON {type(data).__name__}")
    if isinstance(data, dict) and data.get("kind") not in (None, "Percepts"):
        got = f"a {shorten(str(data['kind']))} message"
    raise ProgramError([Diagnostic(source, 1, 1, "expected a list of percepts, an object whose "
                                   '"percepts" is that list, or a `teleo echo` line of a '
                                   f"Percepts message; got {got}")])


def _percept(node: object, source: str, diags: list[Diagnostic]) -> Percept | None:
    def bad(msg: str) -> None:
        diags.append(Diagnostic(source, node.line, node.col, msg))
    if not isinstance(node, SList) or len(node.items) < 2:
        bad(f"expected a percept (type id attr value ...), got {to_text(node)}")
        return None
    if not all(isinstance(x, Atom) and is_const(x.value) for x in node.items):
        bad(f"percept {to_text(node)}: items must be symbols or numbers (no variables or lists)")
        return None
    vals = [x.value for x in node.items]
    if len(vals) % 2:
        bad(f"percept {to_text(node)}: attribute {vals[-1]} has no value")
        return None
    try:
        return Percept.from_list(vals)
    except LangError as exc:
        bad(shorten(str(exc), 300))
        return None


def _json_percepts(text: str, source: str) -> tuple[Percept, ...]:
    """JSON neutral lists, read within the limits (limits.read_json: no NaN or infinity), in
    one of the forms ``percept_list`` accepts."""
    lines = [ln for ln in text.splitlines() if ln.strip()]
    if len(lines) > 1 and all(ln.lstrip().startswith("{") for ln in lines):
        raise ProgramError([Diagnostic(source, 2, 1, f"{len(lines)} JSON lines (saved "
                                       "messages?): keep one, e.g. `teleo echo ... --count 1`"
                                       " or one line of the file")])
    out, diags = [], []
    for i, item in enumerate(percept_list(read_json(text, source), source)):
        try:
            out.append(Percept.from_list(item))
        except LangError as exc:
            diags.append(Diagnostic(source, 1, 1, f"item {i}: {shorten(str(exc), 300)}"))
            if len(diags) >= MAX_DIAGNOSTICS:
                break
    if diags:
        raise ProgramError(diags)
    return tuple(out)
