"""The goal-entry process's inputs (agents/processes/goal_inputs.py) on a real bus: the
intentions wait until the process wakes for a world state and are then all there, each
agent's in the order it sent them, none lost; a payload that does not decode is left."""

from __future__ import annotations

import logging
import time
import uuid

from agents.processes.goal_inputs import GoalInputs
from bus import keys
from bus.config import BusConfig
from bus.messages import Intention, WorldState
from bus.node import open_node
from bus.router import spawn_router


def test_intentions_wait_for_the_state_and_come_all_in_order():
    run = "t" + uuid.uuid4().hex[:8]
    agents = ("A", "B")
    with spawn_router() as router:
        cfg = BusConfig(connect=(router.endpoint,))
        with open_node(cfg, run, "goals") as node, open_node(cfg, run, "exec") as other:
            inputs = GoalInputs(node, run, agents, logging.getLogger("test"))
            out = [keys.world_state(run), *(keys.intention(run, a) for a in agents)]
            other.declare(out)
            assert not other.wait_matching(out, 20)
            for t in range(5):
                for a in agents:
                    other.publish(keys.intention(run, a), Intention(
                        other.envelope(t), a, {"goals": [], "actions": []}))
            other.put_raw(keys.intention(run, "B"), b"\x93junk")
            assert inputs.state(0.2) is None   # intentions alone do not wake it
            other.publish(keys.world_state(run), WorldState(other.envelope(5), {}, {}, []))
            deadline = time.monotonic() + 10
            state = None
            while state is None and time.monotonic() < deadline:
                state = inputs.state(0.5)
            got = [(m.agent, m.env.cycle) for m in inputs.intentions()]
            again = list(inputs.intentions())
    assert state is not None and state.env.cycle == 5
    assert got == [(a, t) for a in agents for t in range(5)] and again == []
