"""Action outcomes: what the world reports for each action of the previous cycle
(docs/bus.md, "The cycle"). SCS bodies succeed or fail by them (seed 002, Appendix C:
"an action returns either success or failure") and ROGUE monitors its actions with them
(seed 003, section 6)."""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

from .errors import LangError
from .terms import Action, is_const


class OutcomeStatus(StrEnum):
    DONE = "done"
    FAILED = "failed"


@dataclass(frozen=True, slots=True)
class Outcome:
    """One action's outcome: ``(*gas 30)`` done, or failed with the world's reason."""

    action: Action
    status: OutcomeStatus
    reason: str = ""

    @property
    def ok(self) -> bool:
        return self.status is OutcomeStatus.DONE

    def to_dict(self) -> dict[str, Any]:
        """Neutral form ``{"action": [...], "status": "done"|"failed", "reason": str}``."""
        return {"action": self.action.to_list(), "status": self.status.value,
                "reason": self.reason}

    @classmethod
    def from_dict(cls, d: Any) -> Outcome:
        """Read the neutral form; raises LangError naming the field that is wrong."""
        if not isinstance(d, dict):
            raise LangError(f"outcome {d!r:.80}: expected an object with action, status, reason")
        action = d.get("action")
        if not (isinstance(action, list | tuple) and action and isinstance(action[0], str)
                and all(is_const(v) for v in action[1:])):
            raise LangError(f"outcome {d!r:.80}: action: expected [name, arg, ...], "
                            f"got {action!r:.60}")
        try:
            status = OutcomeStatus(d.get("status"))
        except ValueError:
            raise LangError(f"outcome {d!r:.80}: status: expected 'done' or 'failed', got "
                            f"{d.get('status')!r:.40}") from None
        reason = d.get("reason", "")
        if not isinstance(reason, str):
            raise LangError(f"outcome {d!r:.80}: reason: expected a string, got {reason!r:.40}")
        return cls(Action.from_list(action), status, reason)


def as_outcomes(items: Iterable) -> tuple[Outcome, ...]:
    """Outcome values from Outcomes or neutral dicts; raises LangError for a bad one."""
    return tuple(x if isinstance(x, Outcome) else Outcome.from_dict(x) for x in items)
