"""Random Blocks World problems for the solver's properties (issue 22): states drawn uniformly
(Slaney and Thiebaux, "Blocks World revisited": every arrangement of n named blocks into
towers equally likely), the goal a conjunction of the goal state's (on X Y) facts in a random
order, run by the pure engine against the real pymunk Blocks World (world/blocks), and every
run replayed under STRIPS rules from the start state (the four actions of the standard domain)
to check what the world did and what the summary may claim."""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field

from agents.lang import Engine, EngineState
from world.domain import get_domain

Towers = tuple[tuple[str, ...], ...]   # bottom first


def lah(n: int, k: int) -> int:
    """Arrangements of n named blocks into k towers (unordered set of non-empty stacks)."""
    return math.comb(n - 1, k - 1) * math.factorial(n) // math.factorial(k)


def random_state(rng: random.Random, names: list[str]) -> Towers:
    """A uniformly random arrangement of ``names`` into towers: the number of towers k with
    probability lah(n, k) / sum, then a random order of the blocks cut at k - 1 random places
    (each set of k towers comes from k! such orders and cuts alike)."""
    n = len(names)
    k = rng.choices(range(1, n + 1), weights=[lah(n, k) for k in range(1, n + 1)])[0]
    order = list(names)
    rng.shuffle(order)
    cuts = sorted(rng.sample(range(1, n), k - 1))
    bounds = [0, *cuts, n]
    return tuple(tuple(order[a:b]) for a, b in zip(bounds, bounds[1:], strict=False))


def on_facts(towers: Towers) -> list[tuple[str, str]]:
    return [(t[i + 1], t[i]) for t in towers for i in range(len(t) - 1)]


def conjunction(facts: list[tuple[str, str]]) -> str:
    return "(and " + " ".join(f"(on {a} {b})" for a, b in facts) + ")"


class Strips:
    """The standard four-operator Blocks World: ``under`` maps a block to the block it is on
    or "T", ``holding`` the block in the hand. ``apply`` raises AssertionError on an action
    whose preconditions do not hold."""

    def __init__(self, towers: Towers):
        self.under = {b: (t[i - 1] if i else "T") for t in towers for i, b in enumerate(t)}
        self.holding: str | None = None

    def clear(self, b: str) -> bool:
        return self.holding != b and b not in self.under.values()

    def apply(self, action: list) -> None:
        name, block, other = action
        if name in ("*pickup", "*unstack"):
            assert self.holding is None and self.clear(block), action
            assert self.under[block] == ("T" if name == "*pickup" else other), action
            del self.under[block]
            self.holding = block
        else:
            assert self.holding == block, action
            assert name == "*putdown" or (other in self.under and self.clear(other)), action
            self.under[block] = "T" if name == "*putdown" else other
            self.holding = None

    def holds(self, facts: list[tuple[str, str]]) -> bool:
        return all(self.under.get(a) == b for a, b in facts)

    def key(self) -> tuple:
        return tuple(sorted(self.under.items())), self.holding


@dataclass
class Run:
    """One run: the actions of each cycle, the engine states, the decisions' goal statuses,
    and the STRIPS replay of the actions from the start."""

    actions: list[list[list]] = field(default_factory=list)
    statuses: list[dict[str, str]] = field(default_factory=list)
    notes: list[dict[str, str]] = field(default_factory=list)
    solving: int = 0
    state: EngineState | None = None
    replay: Strips | None = None
    keys: list[tuple] = field(default_factory=list)   # the replayed state after each cycle

    @property
    def plan(self) -> list[list]:
        return [a for acts in self.actions for a in acts]

    def cycles_to(self, goal_id: str) -> int | None:
        """The first cycle in which ``goal_id`` was satisfied, or None."""
        return next((c for c, s in enumerate(self.statuses) if s.get(goal_id) == "satisfied"),
                    None)


def run(engine: Engine, start: Towers, goals: list[tuple[str, int]], cycles: int,
        learned: tuple[str, ...] = (), stop: bool = True) -> Run:
    """Run ``engine`` (the program's own goals removed) with user ``goals`` [(text,
    priority)] on the pymunk Blocks World from ``start`` for at most ``cycles`` cycles
    (``stop``: until every goal is satisfied or failed). A goal that fails is withdrawn the
    next cycle, as the goal-entry process withdraws a user's failed goal; its status stays
    failed in ``statuses``."""
    domain = get_domain("blocks")
    n = sum(len(t) for t in start)
    world = domain.create({"towers": [list(t) for t in start],
                           "table": {"columns": n + 2}}, 0, ["ME"])
    state = engine.initial_state(learned=learned)
    for g in [e.id for e in state.goals]:
        state = engine.remove_goal(state, g)
    for k, (text, priority) in enumerate(goals):
        state = engine.add_goal(state, text, priority, f"g{k + 1}")
    out = Run(replay=Strips(start))
    outcomes: list = []
    for _ in range(cycles):
        percepts = domain.perceive(world.snapshot_dict(), "ME")
        result = engine.cycle(state, percepts, outcomes)
        state = result.state
        acts = [a.to_list() for a in result.decision.actions]
        out.actions.append(acts)
        withdrawn = {g: "failed" for g, s in (out.statuses[-1].items() if out.statuses
                                               else ()) if s == "failed"}
        out.statuses.append({**withdrawn,
                             **{g.id: g.status.value for g in result.decision.goals}})
        out.notes.append({**(out.notes[-1] if out.notes else {}),
                          **{g.id: g.note for g in result.decision.goals}})
        for g in result.decision.goals:
            if g.status.value == "failed":
                state = engine.remove_goal(state, g.id)
        section = result.decision.section("solver")
        out.solving += bool(section is not None and section.solving)
        outcomes = world.apply_actions("ME", acts)
        assert all(o["status"] == "done" for o in outcomes), outcomes
        for a in acts:
            out.replay.apply(a)
        out.keys.append(out.replay.key())
        world.step()
        if stop and all(s in ("satisfied", "failed") for s in out.statuses[-1].values()):
            break
    out.state = state
    return out
