"""A Stage's `early` hook (bus/stage.py): an input of a cycle still incomplete is handed over
while the stage waits for the rest of it (a shared process starts perception and inference on
the world state before the goal lists come), once per cycle still to be handled and never
ahead of an older cycle that may still complete; the step still runs only on the complete
cycle."""

from __future__ import annotations

import time

from bus import keys
from bus.messages import GoalList, Message, WorldState
from bus.node import open_node
from bus.stage import Stage


def _step_until(stage: Stage, want: int, seconds: float = 20.0) -> int | None:
    """Handle input until cycle `want` is done (its number), or None after `seconds`."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if stage.step_once(0.1) == want:
            return want
    return None


def test_early_sees_the_state_before_its_goal_list_and_the_step_the_whole_cycle(cfg, run_id):
    state_key, goals_key = keys.world_state(run_id), keys.goal_list(run_id, "A")
    early: list[tuple[str, int]] = []
    steps: list[tuple[int, list[str]]] = []

    def step(cycle: int, inputs: dict[str, Message]) -> list:
        steps.append((cycle, sorted(inputs)))
        return []

    with open_node(cfg, run_id, "A.agents") as node, open_node(cfg, run_id, "world") as world:
        stage = Stage(node, "A.agents", [state_key, goals_key], step,
                      early=lambda key, msg: early.append((key, msg.env.cycle)))
        stage.start()
        world.declare([state_key, goals_key])
        assert not world.wait_matching([state_key, goals_key], 20)

        def state(t: int) -> WorldState:
            return WorldState(world.envelope(t), {"domain": "driving"}, {}, [], {})

        world.publish(state_key, state(0))
        deadline = time.monotonic() + 20
        while not early and time.monotonic() < deadline:
            assert stage.step_once(0.1) is None   # the goal list is not there yet
        assert early == [(state_key, 0)] and steps == []
        world.publish(goals_key, GoalList(world.envelope(0), "A", ()))
        assert _step_until(stage, 0) == 0
        assert steps == [(0, sorted([state_key, goals_key]))]
        world.publish(state_key, state(0))   # a re-sent state of a cycle already handled
        world.publish(state_key, state(1))
        world.publish(state_key, state(2))   # nothing starts ahead of cycle 1, still to come
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline:
            assert stage.step_once(0.1) is None
        world.publish(goals_key, GoalList(world.envelope(1), "A", ()))
        assert _step_until(stage, 1) == 1
        world.publish(goals_key, GoalList(world.envelope(2), "A", ()))
        assert _step_until(stage, 2) == 2
    assert early in ([(state_key, 0)], [(state_key, 0), (state_key, 1)])
    assert [c for c, _ in steps] == [0, 1, 2]
