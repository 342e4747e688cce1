"""ROGUE's planner and request handling (seed 003), split like pyperplan: ``syntax`` and
``reader`` (the program sections), ``domain`` (operators as plan steps, projection, travel),
``backchain`` (PRODIGY's Back-Chainer on the problem solver's chaining code), ``control``
(search control rules), ``merge`` (the next step by expected travel), ``monitor``
(execution monitoring), ``agenda`` (a decision point), ``rogue`` (the impasse handler, by
name "rogue" in agents.lang.engine.SOLVERS), ``mechanism`` (what it contributes, registered
in agents/lang/registry.py), ``state`` (its part of EngineState) and ``section`` (its part of
a Decision). docs/language.md, "Planning"."""

from .state import PlannerState

__all__ = ["PlannerState"]
