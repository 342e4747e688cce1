"""The loop watch: an agent that comes back to a situation it has already been in
while pursuing the same goal, without the goal having held in between, is going round in a
circle (a lower goal undoing a higher one that is then restored, a learned skill moving a block
to the table and back). The executive notices it within a bounded number of cycles and makes
the goal try something else (agents/lang/execution/circles.py); after MAX_LOOPS such circles in one
episode the goal fails, naming the goals that acted in the circle.

A situation is what the agent perceives, believes and intends at the start of a cycle: a
digest of its percepts, its beliefs and the paths and SCS threads it was running
(``situation``). Percepts count so that a car driving down a long segment, whose beliefs stay
the same while its position changes, is not taken for a circle; intentions count so that a
body that began again because the world changed back by itself (seed 002's do-first) is not
either. The solver's bookkeeping, the cycle and the tallies do not count.

Each goal has a ``Watch`` for its episode, from the cycle it is found unsatisfied to the second
cycle in a row it holds (a goal that holds for one cycle only, undone at once by a higher one
restoring itself, has made no progress) or its removal: the last WINDOW distinct situations,
in order, and a Brent checkpoint (the situation at step 1, 2, 4, 8, ... of the episode) that
catches a circle longer than the window within twice its length. A return counts only where
the goal was pursued (active, in impasse or given up), only after the situation has changed in
between (staying put while the solver thinks is not a circle), and only when every step of the
circle was the agent's own doing: what the program says its actions achieve
(agents/lang/execution/effects.py) was seen to hold in the next situation, or it did not act and the
world stayed as it was. A world that changes back and forth by itself while a teleoreactive
program follows it is not the agent going round in a circle. Plain data in EngineState.loops."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, replace
from typing import Any

from ..core.store import FactStore, PerceptIndex

WINDOW = 32       # distinct situations kept per goal episode [situations]
MAX_LOOPS = 3     # returns tolerated per goal episode before the goal fails [returns]


def situation(pidx: PerceptIndex, store: FactStore, intention: str = "") -> str:
    """A digest (32 hex digits) of the percepts, the concept beliefs and ``intention`` (text
    of what the agent was doing: see ``intention``); equal situations give equal digests in
    any process (no Python hash)."""
    return combined(world(pidx, store), intention)


def combined(world_digest: str, intention: str) -> str:
    """The situation digest of a world digest and an intention."""
    h = hashlib.blake2b(digest_size=16)
    h.update(world_digest.encode())
    h.update(b"|")
    h.update(intention.encode())
    return h.hexdigest()


def world(pidx: PerceptIndex, store: FactStore) -> str:
    """A digest of what the agent perceives and believes (the world part of a situation)."""
    # each percept row and each belief a "\n"-terminated line, the two parts split by "|";
    # hashed in one piece (the same bytes, so the same digest, as hashing line by line), the
    # lines of a part (and a predicate's beliefs) joined in C rather than made one by one
    rows = sorted(map(repr, map(tuple, pidx.rows())))
    parts = ["\n".join(rows), "\n|"] if rows else ["|"]
    facts = store.facts
    for pred in sorted(k for k in facts if isinstance(k, str)):
        lines = store.lines(pred)
        if lines:
            parts += (pred, ("\n" + pred).join(lines), "\n")
    return hashlib.blake2b("".join(parts).encode(), digest_size=16).hexdigest()


@dataclass(frozen=True, slots=True)
class Visit:
    """One situation of an episode: its digest, the cycle it was first seen, the goal whose path
    acted in it (``actor``, "" if none), whether the watched goal was pursued there,
    ``expects``: what the program says the actions taken there achieve (facts as (pred, arg,
    ...)), ``caused``: whether the step to the next situation was the agent's own doing (what
    its actions were to achieve was then seen to hold, or it did not act and the world stayed
    as it was: only its intention moved on), ``world``: the digest of the world part,
    ``held``: whether the watched goal held there."""

    digest: str
    cycle: int
    actor: str = ""
    pursued: bool = False
    expects: tuple[tuple, ...] = ()
    caused: bool = False
    world: str = ""
    held: bool = False

    def to_list(self) -> list:
        return [self.digest, self.cycle, self.actor, self.pursued,
                [list(x) for x in self.expects], self.caused, self.world, self.held]

    @classmethod
    def from_list(cls, d: list) -> Visit:
        return cls(str(d[0]), int(d[1]), str(d[2]), bool(d[3]),
                   tuple(tuple(x) for x in d[4]) if len(d) > 4 else (),
                   bool(d[5]) if len(d) > 5 else False, str(d[6]) if len(d) > 6 else "",
                   bool(d[7]) if len(d) > 7 else False)


@dataclass(frozen=True, slots=True)
class Watch:
    """The loop watch of one goal's episode: ``visits`` (the last WINDOW distinct consecutive
    situations), the Brent checkpoint (``mark`` seen at cycle ``mark_cycle``; it moves after
    ``power`` more situations, and ``power`` doubles), ``loops`` returns found so far and
    ``banned``: skill instances not to be used for this goal again in the episode
    ((goal text, skill number, bindings), bindings as sorted (name, value) pairs)."""

    goal_id: str
    since: int
    visits: tuple[Visit, ...] = ()
    mark: str = ""
    mark_cycle: int = 0
    mark_pursued: bool = False
    power: int = 1
    steps: int = 0
    loops: int = 0
    banned: tuple[tuple[str, int, tuple], ...] = ()
    circle: str = ""
    pending: bool = False
    last: tuple | None = None

    def returned(self, digest: str) -> Visit | None:
        """The earlier visit this situation comes back to (the goal pursued there, another
        situation seen since, every step since the agent's own doing), or None."""
        if not self.visits or self.visits[-1].digest == digest:
            return None
        for k, v in enumerate(self.visits[:-1]):
            if v.digest == digest and v.pursued and all(x.caused for x in self.visits[k:]):
                return v
        if self.mark == digest and self.mark_pursued and self.visits[-1].caused and \
                all(x.caused for x in self.visits if x.cycle >= self.mark_cycle):
            return Visit(digest, self.mark_cycle, "", True)
        return None

    def observed(self, store: FactStore, world_digest: str) -> Watch:
        """This watch with its last step judged (``Visit.caused``) in the world now."""
        if not self.visits:
            return self
        last = self.visits[-1]
        if last.expects:
            caused = all(tuple(x[1:]) in store.get(x[0]) for x in last.expects)
        else:
            caused = bool(last.world) and last.world == world_digest and not last.actor
        if caused == last.caused:
            return self
        return replace(self, visits=self.visits[:-1] + (replace(last, caused=caused),))

    def seen(self, digest: str, cycle: int, actor: str, pursued: bool,
             expects: tuple[tuple, ...], world_digest: str = "", held: bool = False) -> Watch:
        """This watch after the situation ``digest`` (world part ``world_digest``) of
        ``cycle``, in which ``actor`` took actions expected to achieve ``expects`` and the
        goal held (``held``) or not."""
        if self.visits and self.visits[-1].digest == digest:
            last = self.visits[-1]
            merged = replace(last, actor=last.actor or actor, pursued=last.pursued or pursued,
                             expects=expects or last.expects, caused=False, held=held)
            return replace(self, visits=self.visits[:-1] + (merged,))
        visits = (self.visits + (Visit(digest, cycle, actor, pursued, expects, False,
                                       world_digest, held),))[-WINDOW:]
        steps = self.steps + 1
        if not self.mark or steps >= self.power:
            return replace(self, visits=visits, mark=digest, mark_cycle=cycle,
                           mark_pursued=pursued, power=self.power * 2 if self.mark else 1,
                           steps=0)
        return replace(self, visits=visits, steps=steps)

    def since_visit(self, v: Visit) -> tuple[str, ...]:
        """The goals that acted from visit ``v`` on (in order, each once)."""
        later = [x.actor for x in self.visits if x.cycle >= v.cycle and x.actor]
        return tuple(dict.fromkeys(later))

    def to_dict(self) -> dict[str, Any]:
        return {"goal_id": self.goal_id, "since": self.since,
                "visits": [v.to_list() for v in self.visits], "mark": self.mark,
                "mark_cycle": self.mark_cycle, "mark_pursued": self.mark_pursued,
                "power": self.power, "steps": self.steps,
                "loops": self.loops, "circle": self.circle, "pending": self.pending,
                "last": None if self.last is None else
                [self.last[0], self.last[1], [[k, v] for k, v in self.last[2]]],
                "banned": [[g, n, [[k, v] for k, v in b]] for g, n, b in self.banned]}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Watch:
        return cls(str(d["goal_id"]), int(d.get("since", 0)),
                   visits=tuple(Visit.from_list(v) for v in d.get("visits", ())),
                   mark=str(d.get("mark", "")), mark_cycle=int(d.get("mark_cycle", 0)),
                   mark_pursued=bool(d.get("mark_pursued", False)),
                   power=int(d.get("power", 1)), steps=int(d.get("steps", 0)),
                   loops=int(d.get("loops", 0)),
                   banned=tuple((str(g), int(n), tuple((str(k), v) for k, v in b))
                                for g, n, b in d.get("banned", ())),
                   circle=str(d.get("circle", "")), pending=bool(d.get("pending", False)),
                   last=_step(d.get("last")))


@dataclass(frozen=True, slots=True)
class LoopState:
    """Every open episode's watch, by goal id (sorted)."""

    watches: tuple[Watch, ...] = ()

    def watch_of(self, goal_id: str) -> Watch | None:
        return next((w for w in self.watches if w.goal_id == goal_id), None)

    def to_dict(self) -> dict[str, Any]:
        return {"watches": [w.to_dict() for w in self.watches]} if self.watches else {}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> LoopState:
        return cls(tuple(Watch.from_dict(w) for w in d.get("watches", ())))


def intention(paths: tuple, active: tuple, parts: tuple, learned: int) -> str:
    """The part of EngineState that decides what the agent does next in a given world: the
    goals' remembered paths, the goals that acted last, the mechanisms' ``parts`` (the SCS
    threads and choices: Mechanism.intention), and how many skills it has learned (a circle
    that taught a skill may not come round again)."""
    return repr((paths, active, *parts, learned))


def _step(d: Any) -> tuple | None:
    return None if d is None else (str(d[0]), int(d[1]), tuple((str(k), v) for k, v in d[2]))
