"""A program extended by skill clauses given as text (learned skills, seed 000): the clauses
are read and checked against the program's concepts exactly as if they had been written in
it, and numbered after the program's own skills, so a remembered path stays valid."""

from __future__ import annotations

from ..core.program import Program
from ..core.sexpr import read
from .checks import build_program
from .parser import Parts, parse_forms


def extend_program(program: Program, clauses: tuple[str, ...],
                   source: str = "<learned>") -> Program:
    """``program`` plus the skill ``clauses`` (program syntax, one or more clauses per text).
    Raises ProgramError with every problem found, located in ``source``."""
    if not clauses:
        return program
    parts = Parts(program.mechanisms)
    parts.concepts = [c for group in program.concepts.values() for c in group]
    parts.skills = list(program.skills)
    parts.goals = list(program.goals)
    parts.resources = program.resources
    parts.sources = [*program.sources, source]
    parts.sections = {k: list(v) for k, v in program.sections.items()}
    for text in clauses:
        forms, diags = read(text, source)
        parts.diags.extend(diags)
        parse_forms(forms, source, parts)
    return build_program(parts)
