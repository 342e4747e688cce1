"""SCS skill bodies (seed 002, Structured Circuit Semantics, Appendix C). Not built yet:
``ScsState`` is its part of EngineState."""

from .state import ScsState

__all__ = ["ScsState"]
