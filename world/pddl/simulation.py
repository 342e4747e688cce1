"""PddlWorld: the World protocol (world/domain.py) over a PDDL problem's state, the set of its
true atoms. Every agent of the run acts on the one state, in agent order, one action a cycle:
an agent's second action in a cycle fails (`one action a cycle: ... was this cycle's`), as
does an action whose precondition is false (naming the literal), an unknown action, a wrong
arity or object (semantics.py); a failed action changes nothing. ``*wait`` (the safe action of
a silent agent) does nothing and is no action of the plan. No time passes but the
cycle's (1 s a cycle); nothing changes by itself."""

from __future__ import annotations

import pickle
from typing import Any

from world.errors import WorldError
from world.pddl.semantics import Atom, apply, satisfied
from world.pddl.task import Task

DT = 1.0   # [s] a cycle
COUNTERS = ("actions_done", "actions_failed")
WAIT = "*wait"


class PddlWorld:
    """A PDDL problem run as a world; deterministic (the seed is not used)."""

    def __init__(self, task: Task, seed: int, agents: list[str]) -> None:
        if not agents or len(set(agents)) != len(agents):
            raise WorldError(f"PddlWorld: expected distinct agent ids, got {agents}")
        self.task, self.seed, self.cycle = task, seed, 0
        self.state: frozenset[Atom] = task.init
        self.counters = {a: dict.fromkeys(COUNTERS, 0) for a in agents}
        self._acted: dict[str, list[Any]] = {}
        self.plan: list[list[str]] = []   # every action done, in order
        self.actions = tuple(f"*{o.name}" for o in task.domain.operators)  # what it knows
        self.waits = "wait" not in {o.name for o in task.domain.operators}  # *wait: a no-op

    def apply_actions(self, agent: str, actions: list[list[Any]]) -> list[dict[str, Any]]:
        """One outcome per action, in order; never raises."""
        if not isinstance(actions, list | tuple):
            return [{"action": [repr(actions)], "status": "failed",
                     "reason": f"{agent}: expected a list of actions, got {actions!r:.80}"}]
        return [self._one(agent, a) for a in actions]

    def _one(self, agent: str, action: Any) -> dict[str, Any]:
        shown = list(action) if isinstance(action, list | tuple) else [repr(action)]
        if agent not in self.counters:
            return _failed(shown, f"unknown agent {agent!r}; agents: {sorted(self.counters)}")
        if not isinstance(action, list | tuple):
            why = f"expected an action [*name, arg, ...], got {action!r:.80}"
        elif self.waits and list(action) == [WAIT]:
            return {"action": shown, "status": "done", "reason": ""}
        elif agent in self._acted:
            why = f"one action a cycle: {_text(self._acted[agent])} was this cycle's"
        else:
            self.state, why = apply(self.task, self.state, action)
            if not why:
                self._acted[agent] = shown
                self.plan.append([str(x).lstrip("*").lower() for x in action])
        self.counters[agent]["actions_failed" if why else "actions_done"] += 1
        return _failed(shown, f"{agent}: {_text(shown)}: {why}") if why else \
            {"action": shown, "status": "done", "reason": ""}

    def safe_actions(self, agent: str) -> list[list[Any]]:
        """A silent agent waits: ``*wait`` changes nothing and counts as no action (nothing,
        in a domain with an operator called wait)."""
        return [[WAIT]] if self.waits else []

    def inject(self, event: dict[str, Any]) -> dict[str, Any]:
        """The pddl world knows no events."""
        from world.domain import event_outcome

        return event_outcome(event, "the pddl world has no events")

    def step(self) -> None:
        self.cycle += 1
        self._acted = {}

    def goal_holds(self) -> bool:
        return not satisfied(self.task.goal, self.state)

    def snapshot_dict(self) -> dict[str, Any]:
        """Plain data: domain, cycle, time [s], counters, the atoms (sorted), the objects with
        their types (the type first, then those above it), the goal and whether it holds."""
        types = self.task.object_types()
        return {"domain": "pddl", "cycle": self.cycle, "time": round(self.cycle * DT, 9),
                "counters": {a: dict(c) for a, c in self.counters.items()},
                "task": self.task.name, "pddl_domain": self.task.domain.name,
                "atoms": [list(a) for a in sorted(self.state)],
                "objects": [[o, list(types[o])] for o, _ in self.task.objects],
                "goal": [g.text() for g in self.task.goal], "goal_holds": self.goal_holds(),
                "steps": len(self.plan)}

    def checkpoint(self) -> bytes:
        """The whole world, pickled (restore: ``restore``)."""
        return pickle.dumps(self)


def restore(blob: bytes) -> PddlWorld:
    """The inverse of PddlWorld.checkpoint."""
    world = pickle.loads(blob)
    if not isinstance(world, PddlWorld):
        raise WorldError(f"pddl: a checkpoint holds a {type(world).__name__}, not a PddlWorld")
    return world


def _failed(action: list[Any], reason: str) -> dict[str, Any]:
    return {"action": action, "status": "failed", "reason": reason}


def _text(action: list[Any]) -> str:
    return "(" + " ".join(str(x) for x in action) + ")"
