"""Drive SCS bodies cycle by cycle with forced outcomes: the test plays the world, deciding
which of last cycle's actions were done and which failed (seed 002, Appendix C: "an action
returns either success or failure")."""

from __future__ import annotations

from collections.abc import Callable, Iterable

from agents.lang import Engine, load_program_text

PRELUDE = """
(concepts
  ((flag ?f) :percepts ((flag ?f)))       ; switched on by the test's percepts
  ((never ?x) :percepts ((never ?x))))    ; the goal the bodies work for: never achieved
(resources (*a) (*b) (*c) (*d) (*e))
"""


def body_program(body: str, extra: str = "", goals: str = "(never ME)") -> Engine:
    """An engine for one skill of ``(never ?x)`` with ``:body body``, plus ``extra`` forms."""
    text = (PRELUDE + f"(skills ((never ?x) :percepts ((self ?x)) :body {body}))\n"
            + extra + f"\n(goals {goals})\n")
    return Engine(load_program_text(text, "test.tlp"), solver=None)   # SCS alone


Policy = Callable[[int, list], bool]   # (cycle the action was issued, action) -> it fails


def failing(*names: str, times: int | None = None) -> Policy:
    """Actions named ``names`` (without the star) fail (the first ``times`` times each, or
    always)."""
    seen: dict[str, int] = {}

    def policy(cycle: int, action: list) -> bool:
        name = action[0].lstrip("*")
        if name not in names:
            return False
        seen[name] = seen.get(name, 0) + 1
        return times is None or seen[name] <= times
    return policy


def never_fail(cycle: int, action: list) -> bool:
    return False


class Driver:
    """One agent: percepts each cycle from flags, outcomes from a policy."""

    def __init__(self, engine: Engine, seed: int = 0, policy: Policy = never_fail):
        self.engine = engine
        self.state = engine.initial_state(seed=seed)
        self.policy = policy
        self.outcomes: list[dict] = []
        self.result = None

    def step(self, flags: Iterable[str] = (), extra: Iterable[list] = ()) -> list[list]:
        """One cycle; returns the actions (neutral lists)."""
        percepts = [["self", "ME"], *(["flag", f] for f in flags), *extra]
        self.result = self.engine.cycle(self.state, percepts, self.outcomes)
        actions = [a.to_list() for a in self.result.decision.actions]
        cycle = self.state.cycle
        fails = [self.policy(cycle, a) for a in actions]
        self.outcomes = [{"action": a, "status": "failed" if f else "done",
                          "reason": "forced failure" if f else ""}
                         for a, f in zip(actions, fails, strict=True)]
        self.state = self.result.state
        return actions

    def run(self, n: int, flags: Callable[[int], Iterable[str]] | Iterable[str] = ()) -> list:
        """``n`` cycles; each cycle's action names (one string per action, joined by '+')."""
        out = []
        for k in range(n):
            f = flags(k) if callable(flags) else flags
            out.append("+".join(str(a[0]).lstrip("*") + "".join(f" {x}" for x in a[1:])
                                for a in self.step(f)) or "-")
        return out

    @property
    def scs(self) -> dict:
        return self.result.decision.to_dict()["scs"]

    def why(self) -> list[str]:
        return [w.reason for w in self.result.decision.why]
