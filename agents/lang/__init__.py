"""teleo's pure language engine: prioritized teleoreactive logic programs (seed 000, ICARUS).

Imports the standard library only; the only I/O is ``load_program`` reading a file.
"""

from .core.errors import Diagnostic, EvalError, GoalError, LangError, ProgramError, StateError
from .core.explanation import Decision, GoalPath, GoalReport, GoalStatus, PassOver, PathStep
from .core.program import ConceptClause, GoalSpec, Program, Skill
from .core.terms import (
    Action,
    ActionTemplate,
    Belief,
    Expr,
    Literal,
    Percept,
    PerceptPattern,
    Test,
    Var,
)
from .engine import CycleResult, Engine, as_percepts
from .execution.state import EngineState, StoredStep
from .inference.shared_rows import SharedRows
from .loader import load_program, load_program_text, parse_percepts

__all__ = [
    "Action", "ActionTemplate", "Belief", "ConceptClause", "CycleResult", "Decision",
    "Diagnostic", "Engine", "EngineState", "EvalError", "Expr", "GoalError", "GoalPath",
    "GoalReport", "GoalSpec", "GoalStatus", "LangError", "Literal", "PassOver", "PathStep",
    "Percept", "PerceptPattern", "Program", "ProgramError", "SharedRows", "Skill", "StateError",
    "StoredStep",
    "Test", "Var", "as_percepts", "load_program", "load_program_text", "parse_percepts",
]
