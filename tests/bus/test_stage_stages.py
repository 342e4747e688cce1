"""A Stage that runs several stages' steps (a shared process, agents/processes/shared.py): the
step's outputs carry each stage's stats as a stage of its own carries them (issue 36), no
ProcessStats goes out while the cycles come fast, and once idle after a cycle the Stage says
alone, for each stage, that the cycle is done (the clock's culprit in a stall)."""

from __future__ import annotations

import time

from bus import keys
from bus.messages import Actions, Envelope, GoalList, Message, Percepts, WorldState
from bus.node import open_node
from bus.stage import Stage

STAGES = ("A.perception", "A.executive")


def test_a_shared_stage_carries_its_stages_stats_and_says_alone_once_idle(cfg, run_id):
    state_key, goals_key = keys.world_state(run_id), keys.goal_list(run_id, "A")
    p_key, a_key = keys.percepts(run_id, "A"), keys.actions(run_id, "A")

    def step(cycle: int, inputs: dict[str, Message]) -> list[tuple[str, Message]]:
        own = {"A.perception": [1.5, 0]}
        carried = {**inputs[goals_key].stats, **own, "A.executive": [0.5, 0]}
        return [(p_key, Percepts(Envelope.now(run_id, cycle, "A.perception"), "A", (),
                                 stats=own)),
                (a_key, Actions(Envelope.now(run_id, cycle, "A.executive"), "A", (),
                                stats=carried))]

    with open_node(cfg, run_id, "agents1") as node, open_node(cfg, run_id, "world") as world:
        stage = Stage(node, "agents1", [state_key, goals_key], step, outputs=[a_key],
                      stages=STAGES, quiet_s=0.5)
        alone = world.subscribe(keys.all_stats(run_id))
        actions = world.subscribe(a_key)
        world.declare([state_key, goals_key])
        stage.start()
        assert not world.wait_matching([state_key, goals_key], 20)
        for t in range(3):
            world.publish(state_key, WorldState(world.envelope(t), {}, {}, []))
            world.publish(goals_key, GoalList(world.envelope(t), "A", (), {"goals": [0.25, 0]}))
            deadline = time.monotonic() + 20
            while stage.step_once(0.05) != t and time.monotonic() < deadline:
                pass
        got = [actions.get(timeout=5.0) for _ in range(3)]
        assert alone.get(timeout=0.2) is None   # fast cycles: no stats message of their own
        assert stage.step_once(0.6) is None   # idle past quiet_s: each stage's stats of
        #                                        cycle 2, alone
        said = []
        while (msg := alone.get(timeout=1.0)) is not None:
            said.append((msg.process, msg.env.cycle, msg.compute_ms))
    assert [m.stats for m in got] == [{"goals": [0.25, 0], "A.perception": [1.5, 0],
                                       "A.executive": [0.5, 0]}] * 3
    assert said == [("A.perception", 2, 1.5), ("A.executive", 2, 0.5)]
