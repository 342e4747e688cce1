"""What running a step gives (agents/lang/scs/constructs.py): acted, idle, ended with success
or failure; and small helpers on bindings shared by the construct modules."""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

from ..core.terms import Var
from ..execution.paths import show
from .state import Frame, ThreadStatus


class R(StrEnum):
    ACT = "act"     # an atomic step was issued (or a subgoal's path acts) this cycle
    IDLE = "idle"   # nothing this cycle: waiting or inactive; the frame is kept
    OK = "ok"       # the step ended with success
    FAIL = "fail"   # the step ended with failure


@dataclass(frozen=True, slots=True)
class Res:
    kind: R
    frame: Frame | None = None
    why: str = ""
    status: ThreadStatus = ThreadStatus.WAITING


OK = Res(R.OK)


def fail(why: str) -> Res:
    return Res(R.FAIL, None, why)


def env_with(env: dict, pairs: tuple) -> dict:
    """``env`` extended by stored ((name, value), ...) bindings."""
    if not pairs:
        return env
    out = dict(env)
    for k, v in pairs:
        out[Var(k)] = v
    return out


def added(sol: dict, env: dict) -> tuple:
    """The bindings ``sol`` makes beyond ``env``, as sorted ((name, value), ...)."""
    return tuple(sorted((v.name, x) for v, x in sol.items() if v not in env
                        and not isinstance(x, Var)))


def show_conds(conds: tuple, env: dict | None = None) -> str:
    """Conditions as text, with the variables bound in ``env`` replaced by their values."""
    return "(" + " ".join(show(c, env or {}) for c in conds) + ")"
