"""Discount factors of do-best alternatives (seed 002, Appendix A, "Learning").

"The discount factor, a value between 0 and 1, is initially set to 1. The discount factor is
multiplied by the evaluated value of the utility function to select the action to do next
... The agent updates the value of discount factor for each action over the repeated courses
of execution using reinforcement-based learning methods."

The rule here: each time an alternative's step ends, its factor ``d`` moves toward the
measured result ``r`` by a fixed fraction (an exponentially weighted average, the simplest
reinforcement rule that keeps ``d`` in [0, 1] and forgets old evidence at a known rate):

    d <- d + LEARNING_RATE * (r - d)

with ``r = 0`` when the step failed, and when it succeeded ``r = 1``, or the alternative's
``:reward`` expression evaluated on the percepts after the step, clipped to [0, 1]. An
alternative abandoned because its condition stopped holding is not a result: ``d`` stays.
After k failures in a row ``d = (1 - LEARNING_RATE) ** k`` (0.7, 0.49, 0.34, ...), so an
alternative with utility 10 that keeps failing ranks below one with utility 6 that succeeds
after two failures; a success takes it back toward 1 at the same rate.
"""

from __future__ import annotations

from dataclasses import replace

from .state import Choice

LEARNING_RATE = 0.3
"""Fraction of the gap between the factor and the measured result closed per execution."""


def reward_value(raw: object) -> float:
    """A :reward expression's value as a measured result in [0, 1] (a non-number gives 0)."""
    if isinstance(raw, bool) or not isinstance(raw, int | float):
        return 0.0
    return min(1.0, max(0.0, float(raw)))


def reinforce(factor: float, result: float, rate: float = LEARNING_RATE) -> float:
    """The factor after one execution whose measured result is ``result`` (in [0, 1])."""
    new = factor + rate * (result - factor)
    return round(min(1.0, max(0.0, new)), 6)


def record(choice: Choice, succeeded: bool, result: float) -> Choice:
    """``choice`` after one execution of its step ended (success or failure)."""
    return replace(choice, factor=reinforce(choice.factor, result if succeeded else 0.0),
                   succeeded=choice.succeeded + succeeded, failed=choice.failed + (not succeeded))
