"""Whether an SCS state read back (an agent's memory, handed back by the world each cycle;
docs/bus.md, "Agent memory") fits the program it is to run in: each thread's skill has a
body, and each world-model fact of a predicate the program defines or asserts has its arity
(facts of other predicates are the model's own). A state made by this program always fits;
one that does not would send the interpreter past the end of a body (seed 002's constructs
index their steps) or the matcher past the end of a fact."""

from __future__ import annotations

from typing import Any

from ..core.errors import StateError
from .checks import model_facts
from .state import Frame, ScsState, Thread
from .syntax import children, node_at


def model_arity(program: Any) -> dict[str, int]:
    """Predicate -> arity of every fact a world model of ``program`` may hold: its concepts'
    instances and the facts its bodies assert (seed 002)."""
    out = dict(program.arity)
    for update in model_facts(program.skills):
        out.setdefault(update.fact.pred, len(update.fact.args))
    return out


def check_model(model: tuple[tuple, ...], arity: dict[str, int]) -> tuple[tuple, ...]:
    """``model`` if each fact of a predicate in ``arity`` (model_arity) has that arity (a fact
    of another predicate is only asserted: inference keeps it as it is); else StateError
    naming the fact."""
    for fact in model:
        want = arity.get(fact[0])
        if want is not None and want != len(fact) - 1:
            raise StateError(f"world-model fact {list(fact)!r:.80}: {fact[0]} takes {want} "
                             f"argument(s), got {len(fact) - 1}")
    return model


def check_fits(scs: ScsState, program: Any) -> ScsState:
    """``scs`` if it fits ``program`` (see the module); else StateError naming the thread
    and the frame field, or the fact, that does not."""
    for t in scs.threads:
        _thread(t, program.skills)
    check_model(scs.model, model_arity(program))
    return scs


def _thread(t: Thread, skills: tuple[Any, ...]) -> None:
    where = f"scs thread {t.key!r:.60}"
    if not 0 <= t.skill < len(skills) or skills[t.skill].body is None:
        raise StateError(f"{where}: skill: {t.skill} is not a skill with a :body (the "
                         f"program has {len(skills)} skills)")
    body, frame, at = skills[t.skill].body, t.root, ()
    while frame is not None:
        _frame(where, body, frame, at)
        at = (*frame.at, frame.cur)
        frame = frame.child


def _frame(where: str, body: object, f: Frame, at: tuple) -> None:
    if f.at != at:
        raise StateError(f"{where}: at: expected {list(at)}, got {list(f.at)}")
    try:
        n = len(children(node_at(body, f.at)))
    except (IndexError, TypeError):
        raise StateError(f"{where}: at: {list(f.at)} is not a step of the body") from None
    if not -1 <= f.cur < n:
        raise StateError(f"{where}: cur: expected -1 .. {n - 1}, got {f.cur}")
    if f.child is not None and f.cur < 0:
        raise StateError(f"{where}: child: a running child needs cur >= 0, got {f.cur}")
    for name in ("done", "failed"):
        bad = [i for i in getattr(f, name) if not 0 <= i < n]
        if bad:
            raise StateError(f"{where}: {name}: expected steps 0 .. {n - 1}, got {bad[0]}")
