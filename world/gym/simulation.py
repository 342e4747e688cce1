"""GymWorld: the World protocol (world/domain.py) on one Gymnasium environment, stepped once
a cycle with the agent's action; the episode is reset with the run's seed, so a run is
reproducible (same seed, same trace), and it ends the run when the episode is over.

An action is one of the environment's own, by name: `*left`, `*right`, `*forward`,
`*pickup`, `*drop`, `*toggle`, `*done` (MiniGrid's), without arguments, one a cycle. A
malformed one fails with a reason and the environment is not stepped (the episode goes on).
A cycle without an action, or with teleo's own `*wait` (the safe action of an agent whose
actions did not arrive), does not step the environment either.
"""

from __future__ import annotations

import pickle
from typing import Any

from world.domain import Outcome
from world.errors import ConfigError
from world.gym.config import GymConfig, make_env
from world.gym.families import family

WAIT = "*wait"   # teleo's own: this cycle does not step the environment (the safe action)
COUNTERS = ("steps", "actions_failed", "lava", "collisions", "missions")


class GymWorld:
    """One environment, one agent (the scenario's only one)."""

    def __init__(self, config: GymConfig, seed: int, agents: list[str]) -> None:
        if len(agents) != 1:
            raise ConfigError(f"[[agents]]: the gymnasium domain runs one agent per "
                              f"environment, got {len(agents)} ({', '.join(agents)})")
        self.config, self.seed, self.agent = config, seed, agents[0]
        self.env = make_env(config)
        try:
            self.env.reset(seed=seed)
        except (TypeError, ValueError, AssertionError, IndexError) as exc:
            raise ConfigError(f"[world] env_kwargs = {config.env_kwargs!r}: {config.env} "
                              f"cannot make an episode with them ({type(exc).__name__}: "
                              f"{exc})") from exc
        self.cycle = 0
        self.counters = {name: 0 for name in COUNTERS}
        self.episode: dict[str, Any] = {"terminated": False, "truncated": False,
                                        "reward": 0.0, "steps": 0}
        self.pending: int | None = None
        self._last = self.family.capture(self.env.unwrapped)

    @property
    def family(self) -> Any:
        """The family module (world/gym/families): its ACTIONS, capture, perceive."""
        return family(self.config.family)

    # --- the World protocol -------------------------------------------------------------
    def apply_actions(self, agent: str, actions: list[list[Any]]) -> list[Outcome]:
        """Validate this cycle's actions: the first well-formed one is stepped with (step)."""
        outcomes = []
        for action in actions:
            reason = self._problem(agent, action)
            if not reason and self.pending is not None:
                reason = "one action a cycle: an action was already taken this cycle"
            if reason:
                self.counters["actions_failed"] += 1
                outcomes.append({"action": list(action) if isinstance(action, list | tuple)
                                 else [repr(action)], "status": "failed", "reason": reason})
                continue
            if action[0] != WAIT:
                self.pending = self.family.ACTIONS.index(str(action[0])[1:])
            outcomes.append({"action": list(action), "status": "done", "reason": ""})
        return outcomes

    def _problem(self, agent: str, action: Any) -> str:
        if agent != self.agent:
            return f"unknown agent {agent!r} (this environment's agent is {self.agent})"
        if self.over:
            return "the episode is over"
        if not isinstance(action, list | tuple) or not action or not isinstance(action[0], str):
            return f"malformed action {action!r}: expected [\"*name\"]"
        name = action[0]
        if name != WAIT and (not name.startswith("*") or name[1:] not in self.family.ACTIONS):
            return (f"unknown action {name!r}; known: "
                    f"{', '.join('*' + a for a in self.family.ACTIONS)}, {WAIT}")
        if len(action) > 1:
            return f"{name} takes no arguments, got {list(action[1:])!r}"
        return ""

    def safe_actions(self, agent: str) -> list[list[Any]]:
        """*wait: the environment is not stepped."""
        return [[WAIT]]

    def inject(self, event: dict[str, Any]) -> dict[str, Any]:
        from world.domain import event_outcome

        return event_outcome(event, "the gymnasium domain has no events")

    def step(self) -> None:
        """Step the environment with this cycle's action (none: it stays as it is)."""
        self.cycle += 1
        if self.pending is None:
            return
        action, self.pending = self.pending, None
        env = self.env.unwrapped
        front = env.grid.get(*env.front_pos)
        bumps = (action == env.actions.forward and front is not None
                 and not front.can_overlap())
        _, reward, terminated, truncated, _ = self.env.step(action)
        self.counters["steps"] += 1
        self.counters["collisions"] += int(bumps and getattr(env, "obstacles", None) is not None)
        here = env.grid.get(*env.agent_pos)
        self.counters["lava"] += int(here is not None and here.type == "lava")
        self.episode = {"terminated": bool(terminated), "truncated": bool(truncated),
                        "reward": round(self.episode["reward"] + float(reward), 6),
                        "steps": int(env.step_count)}
        self.counters["missions"] += int(bool(terminated) and float(reward) > 0)
        self._last = self.family.capture(env)

    @property
    def over(self) -> bool:
        """The episode has terminated or been truncated."""
        return bool(self.episode["terminated"] or self.episode["truncated"])

    def snapshot_dict(self) -> dict[str, Any]:
        return {"domain": "gymnasium", "cycle": self.cycle, "time": float(self.cycle),
                "counters": {self.agent: dict(self.counters)}, "env": self.config.env,
                "agent": self.agent, "state": self._last, "episode": dict(self.episode)}

    def checkpoint(self) -> bytes:
        """The whole world (the environment included) as a pickle."""
        return pickle.dumps(self)
