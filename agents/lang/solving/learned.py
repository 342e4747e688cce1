"""Learned-skill files: the skills an agent learned (EngineState.learned), written out in
program syntax, each clause after a comment saying when and from which problem it was
learned, under a header naming the program they extend. ``teleo check PROGRAM LEARNED``
checks one against its program; ``--learned FILE`` starts a run from one.

Reading a file checks it as part of its program (``extend_program``), so a malformed file is
refused with file:line:col and a file learned for another program is refused naming the
concept this program does not define. It may hold skill clauses only."""

from __future__ import annotations

from ..core.errors import Diagnostic, ProgramError
from ..core.program import Program
from ..core.sexpr import Atom, SList, read, to_text
from ..reading.extend import extend_program
from ..reading.parser import SKILL_MARKERS

HEADER = "; teleo learned skills"


def learned_text(clauses: tuple[str, ...], program: str) -> str:
    """The file for ``clauses`` (EngineState.learned) learned with the program at path
    ``program``."""
    head = (f"{HEADER} for {program}\n; learned on impasse by the means-ends problem solver "
            f"(seed 000, \"Problem Solving and Skill Learning\").\n"
            f"; Check: teleo check {program} THIS-FILE; reuse: --learned THIS-FILE\n")
    return head + "".join(f"\n{c.strip()}\n" for c in clauses)


def clause_heads(text: str) -> list[str]:
    """The head of every clause in a learned file, as text (for summaries)."""
    forms, _ = read(text, "<learned>")
    return [to_text(f.items[0]) for f in forms
            if isinstance(f, SList) and f.items and isinstance(f.items[0], SList)]


def program_named(text: str) -> str:
    """The program a learned file says it was learned with (its first line), or ""."""
    first = text.split("\n", 1)[0]
    return first[len(HEADER) + len(" for "):].strip() if first.startswith(f"{HEADER} for ") \
        else ""


def is_learned_text(text: str) -> bool:
    """True for a file written by ``learned_text``."""
    return text.startswith(HEADER)


def read_learned(program: Program, text: str, source: str) -> tuple[str, ...]:
    """The clauses of a learned file (each with the comment above it), checked against
    ``program``. Raises ProgramError with every problem, located in ``source``."""
    forms, diags = read(text, source)
    for f in forms:
        if not (isinstance(f, SList) and f.items and isinstance(f.items[0], SList)
                and any(isinstance(x, Atom) and x.value in SKILL_MARKERS for x in f.items)):
            diags.append(Diagnostic(source, f.line, f.col, "a learned file holds skill clauses "
                                    f"((head ...) :start ... :subgoals ...) only, got "
                                    f"{to_text(f)[:60]}"))
    if any(d.severity == "error" for d in diags):
        raise ProgramError(diags)
    extend_program(program, (text,), source)
    return _clauses(text, forms)


def _clauses(text: str, forms: list) -> tuple[str, ...]:
    """Split ``text`` at its top-level forms; each clause keeps the comment lines directly
    above it (the file header, separated by a blank line, is left out)."""
    if not forms:  # nothing learned: the header alone
        return ()
    lines = text.splitlines()
    starts = []
    for f in forms:
        first = f.line - 1
        while first > 0 and lines[first - 1].lstrip().startswith(";"):
            first -= 1
        starts.append(first)
    ends = starts[1:] + [len(lines)]
    return tuple("\n".join(lines[a:b]).strip() for a, b in zip(starts, ends, strict=True))
