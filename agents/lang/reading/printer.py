"""Programs back to text in the language's own syntax (seed 000, Tables 1, 2, 5, 6).

``load_program_text(program_text(p))`` gives a program equal to ``p`` clause for clause (locations
aside): concept clauses are printed grouped by predicate in the order the predicates were first
defined (their order never matters to inference), skills in program order (it matters to the
executive), then resources and goals. A skill's :tests were folded into its :start when it was
read and are printed there, which reads back the same. Pure: no I/O.
"""

from __future__ import annotations

from ..core.program import ConceptClause, Program, Skill

_INDENT = "   "


def clause_text(clause: ConceptClause | Skill) -> str:
    """One clause as text, ``((head ...) :key (...) ...)``, one keyword per line."""
    if isinstance(clause, Skill):
        fields = ((":percepts", clause.percepts), (":start", clause.start),
                  (":requires", clause.requires), (":subgoals", clause.subgoals),
                  (":actions", clause.actions), (":effects", clause.effects))
    else:
        fields = ((":percepts", clause.percepts), (":relations", clause.relations),
                  (":tests", clause.tests))
    lines = [f"({clause.head}"]
    lines += [f"{_INDENT}{key} ({' '.join(str(x) for x in items)})"
              for key, items in fields if items]
    return "\n".join(lines) + ")"


def program_text(program: Program, header: str = "") -> str:
    """The whole program as a file's text; ``header`` lines become ``;`` comments on top."""
    out = [f"; {line}".rstrip() for line in header.splitlines()]
    if out:
        out.append("")
    concepts = [c for clauses in program.concepts.values() for c in clauses]
    out += _section("concepts", [clause_text(c) for c in concepts])
    out += _section("skills", [clause_text(s) for s in program.skills])
    if program.resources is not None:
        entries = [f"({' '.join([name, *sorted(res)])})"
                   for name, res in program.resources.items()]
        out += _section("resources", entries)
    out += _section("goals", [str(g.literal) for g in program.goals])
    return "\n".join(out) + "\n"


def _section(name: str, items: list[str]) -> list[str]:
    if not items:
        return []
    body = [_indent(text) for text in items]
    body[-1] += ")"
    return [f"({name}", *body, ""]


def _indent(text: str) -> str:
    return "\n".join("  " + line for line in text.splitlines())


__all__ = ["clause_text", "program_text"]
