"""Errors of the language engine: one root exception, diagnostics with file:line:col."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Diagnostic:
    """One problem found in a program or percept text, located at file:line:col (1-based)."""

    source: str
    line: int
    col: int
    message: str
    severity: str = "error"  # "error" | "warning"

    def __str__(self) -> str:
        tag = "warning: " if self.severity == "warning" else ""
        where = f"{self.source}:{self.line}:{self.col}" if self.line else self.source  # 0: a file
        return f"{where}: {tag}{self.message}"


class LangError(Exception):
    """Root of every error raised by agents.lang."""


SHOWN_DIAGNOSTICS = 200
"""At most this many diagnostics are written in a ProgramError's message; the rest are counted."""


class ProgramError(LangError):
    """A program (or percept text) is invalid; carries every diagnostic found, all of them
    (its message shows the first SHOWN_DIAGNOSTICS and counts the others)."""

    def __init__(self, diagnostics: list[Diagnostic]):
        self.diagnostics = list(diagnostics)
        lines = [str(d) for d in self.diagnostics[:SHOWN_DIAGNOSTICS]]
        if len(self.diagnostics) > SHOWN_DIAGNOSTICS:
            lines.append(f"... and {len(self.diagnostics) - SHOWN_DIAGNOSTICS} more")
        super().__init__("\n".join(lines))

    @property
    def errors(self) -> list[Diagnostic]:
        """Only the diagnostics of severity error."""
        return [d for d in self.diagnostics if d.severity == "error"]


class GoalError(LangError):
    """A run-time goal request is invalid (unknown concept, wrong arity, bad syntax, unknown id)."""


class StateError(LangError):
    """An EngineState dictionary cannot be read back (wrong shape or version)."""


class EvalError(LangError):
    """An arithmetic expression could not be evaluated (type mismatch, division by zero)."""
