"""SCS skill bodies (seed 002, Structured Circuit Semantics, Appendix C): the step tree
(syntax.py) read from ``:body`` (reader.py) and checked (checks.py); the interpreter, one
thread's tick (constructs.py, choosing.py, results.py); threads in the engine (runner.py);
discount factors (learning.py); the state kept in EngineState.scs (state.py); the "scs"
section of a decision (section.py). docs/language.md, "Skill bodies", is the reference."""

from .state import ScsState

__all__ = ["ScsState"]
