"""The SCS interpreter's part of EngineState: what it keeps between cycles and across a restart
of the executive process. Body threads (each a chain of frames, one per running construct,
outermost first: position, choice, achieved and failed substeps, retries, rounds, bindings,
the action awaiting its outcome), the discount factor and record of every do-best
alternative (seed 002, Appendix A, "Learning"), the world model (asserted facts) and a tally
of what the bodies did. Plain data in ``to_dict``, read back exactly by ``from_dict``."""

from __future__ import annotations

import math
from bisect import bisect_left
from dataclasses import dataclass, field, replace
from enum import StrEnum
from typing import Any

from ..core.errors import StateError
from ..core.limits import INT_MAX, INT_MIN
from ..core.terms import is_const, sort_key


class ThreadStatus(StrEnum):
    """What a body thread did in the last cycle it ran."""

    ACTING = "acting"        # issued an atomic step, or acts through a subgoal's path
    WAITING = "waiting"      # at a (wait ...) point, or its actions' resources are taken
    INACTIVE = "inactive"    # a :while/:until or every do-first/do-best condition is false
    SUCCEEDED = "succeeded"  # the body ended with success
    FAILED = "failed"        # the body ended with failure


@dataclass(frozen=True, slots=True)
class Frame:
    """One running step. ``at``: its address in the body; ``bind``: bindings its conditions
    made, ((name, value), ...); ``cur``: the running child (do/repeat: position; the others:
    the chosen alternative; -1: none); ``done``/``failed``: children achieved / failed;
    ``alt``: bindings of the chosen do-first/do-best alternative's conditions; ``tries``:
    failures retried; ``rounds``: repeat rounds done; ``since``: cycle the current child
    started; ``began``: cycle the current repeat round started; ``pending``: the actions
    issued (neutral lists) at cycle ``issued``, awaiting their outcome; ``outcome``: "done"
    or "failed" once known, "running" while the world has not reported one (the action is
    sent again, which continues a lasting operation), ``reason`` the world's reason."""

    at: tuple[int, ...]
    bind: tuple = ()
    cur: int = -1
    done: tuple[int, ...] = ()
    failed: tuple[int, ...] = ()
    alt: tuple = ()
    tries: int = 0
    rounds: int = 0
    since: int = -1
    began: int = -1
    child: Frame | None = None
    pending: tuple = ()
    issued: int = -1
    outcome: str = ""
    reason: str = ""

    def but(self, **changes: Any) -> Frame:
        """A copy with ``changes`` (dataclasses.replace, without its per-call field scan:
        the interpreter makes several per step)."""
        new = object.__new__(Frame)
        for name in _FIELDS:
            object.__setattr__(new, name, changes[name] if name in changes
                               else getattr(self, name))
        return new

    def chain(self) -> list[Frame]:
        """This frame and its running descendants, outermost first."""
        out, f = [], self
        while f is not None:
            out.append(f)
            f = f.child
        return out

    def leaf(self) -> Frame:
        return self.chain()[-1]

    def with_leaf(self, leaf: Frame) -> Frame:
        """This chain with its innermost frame replaced by ``leaf``."""
        if self.child is None:
            return leaf
        return self.but(child=self.child.with_leaf(leaf))

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"at": list(self.at)}
        for name, empty in _FRAME_DEFAULTS.items():
            v = getattr(self, name)
            if v != empty:
                d[name] = [list(x) for x in v] if name in ("bind", "alt", "pending") else \
                    list(v) if isinstance(v, tuple) else v
        if self.child is not None:
            d["child"] = self.child.to_dict()
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Frame:
        child = d.get("child")
        return cls(tuple(_int(i) for i in d["at"]),
                   tuple((str(k), _const(v)) for k, v in d.get("bind", ())),
                   _int(d.get("cur", -1)), tuple(_int(i) for i in d.get("done", ())),
                   tuple(_int(i) for i in d.get("failed", ())),
                   tuple((str(k), _const(v)) for k, v in d.get("alt", ())),
                   _int(d.get("tries", 0)), _int(d.get("rounds", 0)), _int(d.get("since", -1)),
                   _int(d.get("began", -1)),
                   None if child is None else cls.from_dict(child),
                   tuple(tuple(_const(x) for x in a) for a in d.get("pending", ())),
                   _int(d.get("issued", -1)), str(d.get("outcome", "")),
                   str(d.get("reason", "")))


_FIELDS = ("at", "bind", "cur", "done", "failed", "alt", "tries", "rounds", "since", "began",
           "child", "pending", "issued", "outcome", "reason")
_FRAME_DEFAULTS = {"bind": (), "cur": -1, "done": (), "failed": (), "alt": (), "tries": 0,
                   "rounds": 0, "since": -1, "began": -1, "pending": (), "issued": -1,
                   "outcome": "", "reason": ""}


@dataclass(frozen=True, slots=True)
class Thread:
    """The running body of one skill for one goal. ``key``: goal id, goal instance and skill
    number; ``root``: the frame chain (None once the body ended); ``note``: what happened in
    the last cycle it ran (for the explanation)."""

    key: str
    goal_id: str
    goal: str
    skill: int
    skill_name: str
    root: Frame | None
    status: ThreadStatus
    note: str = ""
    started: int = 0
    last: int = 0

    def to_dict(self) -> dict[str, Any]:
        return {"key": self.key, "goal_id": self.goal_id, "goal": self.goal,
                "skill": self.skill, "skill_name": self.skill_name,
                "root": None if self.root is None else self.root.to_dict(),
                "status": self.status.value, "note": self.note, "started": self.started,
                "last": self.last}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Thread:
        root = d.get("root")
        return cls(str(d["key"]), str(d["goal_id"]), str(d["goal"]), _int(d["skill"]),
                   str(d["skill_name"]), None if root is None else Frame.from_dict(root),
                   ThreadStatus(d["status"]), str(d.get("note", "")), _int(d.get("started", 0)),
                   _int(d.get("last", 0)))


@dataclass(frozen=True, slots=True)
class Choice:
    """A do-best alternative's record: its discount factor in [0, 1] (initially 1, seed 002,
    Appendix A) and how often it was chosen, succeeded and failed. ``key`` names the skill and
    the alternative's address; ``label`` is its step and where it is written."""

    key: str
    label: str
    factor: float = 1.0
    chosen: int = 0
    succeeded: int = 0
    failed: int = 0

    def to_dict(self) -> dict[str, Any]:
        return {"key": self.key, "label": self.label, "factor": self.factor,
                "chosen": self.chosen, "succeeded": self.succeeded, "failed": self.failed}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Choice:
        factor = float(d.get("factor", 1.0))
        if not 0.0 <= factor <= 1.0:
            raise StateError(f"scs choice {d.get('key')!r}: factor {factor} is not in [0, 1]")
        return cls(str(d["key"]), str(d.get("label", "")), factor, _int(d.get("chosen", 0)),
                   _int(d.get("succeeded", 0)), _int(d.get("failed", 0)))


@dataclass(frozen=True, slots=True)
class ScsState:
    """Threads (sorted by key), do-best choices (sorted by key), the world model (facts as
    (pred, arg, ...) tuples, sorted) and a tally ((what, count), ...) of the bodies' work."""

    threads: tuple[Thread, ...] = ()
    choices: tuple[Choice, ...] = ()
    model: tuple[tuple, ...] = ()
    tally: tuple[tuple[str, int], ...] = ()
    _keys: tuple | None = field(default=None, init=False, compare=False, repr=False)

    def keys(self) -> tuple[str, ...]:
        """The threads' keys, in order (cached: a lookup is a binary search)."""
        if self._keys is None:
            object.__setattr__(self, "_keys", tuple(t.key for t in self.threads))
        return self._keys

    def thread(self, key: str) -> Thread | None:
        keys = self.keys()
        i = bisect_left(keys, key)
        return self.threads[i] if i < len(keys) and keys[i] == key else None

    def choice(self, key: str) -> Choice | None:
        return next((c for c in self.choices if c.key == key), None)

    def with_thread(self, t: Thread) -> ScsState:
        """This state with thread ``t`` stored (replacing the one of the same key)."""
        ts, keys = self.threads, self.keys()
        i = bisect_left(keys, t.key)
        j = i + 1 if i < len(keys) and keys[i] == t.key else i
        new = replace(self, threads=(*ts[:i], t, *ts[j:]))
        object.__setattr__(new, "_keys", (*keys[:i], t.key, *keys[j:]))
        return new

    def counted(self, more: dict[str, int]) -> ScsState:
        """This state with ``more`` added to its tally."""
        if not more:
            return self
        tally = dict(self.tally)
        for k, n in more.items():
            tally[k] = tally.get(k, 0) + n
        return replace(self, tally=tuple(sorted(tally.items())))

    def without(self, keys: set[str]) -> ScsState:
        return replace(self, threads=tuple(t for t in self.threads if t.key not in keys))

    def to_dict(self) -> dict[str, Any]:
        return {"threads": [t.to_dict() for t in self.threads],
                "choices": [c.to_dict() for c in self.choices],
                "model": [list(f) for f in self.model], "tally": dict(self.tally)}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> ScsState:
        """Inverse of to_dict; raises StateError naming what is wrong."""
        try:
            threads = tuple(sorted((Thread.from_dict(t) for t in d.get("threads", ())),
                                   key=lambda t: t.key))
            choices = tuple(sorted((Choice.from_dict(c) for c in d.get("choices", ())),
                                   key=lambda c: c.key))
            return cls(threads, choices, model_of(d.get("model", ())),
                       tuple(sorted((str(k), _int(v)) for k, v in d.get("tally", {}).items())))
        except StateError:
            raise
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise StateError(f"scs state: bad shape ({type(exc).__name__}: {exc})") from None


def model_of(facts: Any) -> tuple[tuple, ...]:
    """World-model facts from neutral lists ``[pred, arg, ...]``, sorted; raises StateError
    for a fact that is not a symbol followed by constants."""
    out = set()
    for f in facts:
        if not (isinstance(f, list | tuple) and f and isinstance(f[0], str)
                and all(is_const(x) for x in f[1:])):
            raise StateError(f"world-model fact {f!r:.80}: expected [pred, arg, ...] with "
                             "symbols and numbers")
        out.add(tuple(f))
    return tuple(sorted(out, key=fact_key))


def fact_key(f: tuple) -> tuple:
    return (f[0], len(f), [sort_key(x) for x in f[1:]])


def _int(v: Any) -> int:
    """A count, cycle or index read back: an integer of at most 64 bits (a larger one could
    not be sent again; a float or a string is not one)."""
    if type(v) is not int or not INT_MIN <= v <= INT_MAX:
        raise StateError(f"scs state: {v!r:.40} is not a 64-bit integer")
    return v


def _const(v: Any) -> Any:
    """A binding's or a pending action's value read back: a symbol or a finite number."""
    if not is_const(v) or (type(v) is float and not math.isfinite(v)):
        raise StateError(f"scs state: {v!r:.40} is not a symbol or finite number")
    return v


def to_memory(scs: ScsState) -> dict[str, Any]:
    """What the executive asks the world to keep for the agent and hand back next cycle
    (docs/bus.md, "Agent memory"): the world model for inference, and the SCS state."""
    d = scs.to_dict()
    return {"model": d.pop("model"), "scs": d}


def from_memory(memory: dict[str, Any]) -> ScsState:
    """Inverse of to_memory; raises StateError naming what is wrong."""
    if not isinstance(memory, dict) or not isinstance(memory.get("scs", {}), dict):
        raise StateError(f"agent memory {memory!r:.80}: expected a map with 'model' and 'scs'")
    return ScsState.from_dict({**memory.get("scs", {}), "model": memory.get("model", ())})
