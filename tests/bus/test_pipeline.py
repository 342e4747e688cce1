"""A clock and three pass-through stages as real processes on a loopback zenoh bus."""

from __future__ import annotations

from functools import partial

from bus_helpers import AGENT, PIPELINE, Stages

from bus import keys
from bus.clock import Clock
from bus.cycle import CycleMode
from bus.messages import WorldState
from bus.node import open_node

N = 25


def state(node, t: int) -> WorldState:
    return WorldState(node.envelope(t), {"cycle": t}, {}, [])


def test_lockstep_cycles_reach_every_stage_once_in_order(cfg, run_id, stages: Stages):
    with open_node(cfg, run_id, "world") as node:
        clock = Clock(node, {AGENT: PIPELINE}, mode=CycleMode.LOCKSTEP, deadline_s=10.0)
        stages.start_agent()
        clock.wait_ready(set(PIPELINE), timeout=30)
        actions = node.subscribe(keys.actions(run_id, AGENT))
        alone = node.subscribe(keys.all_stats(run_id))
        meanwhile: list[int] = []
        reports = [clock.run_cycle(t, state(node, t), meanwhile=partial(meanwhile.append, t))
                   for t in range(N)]
        carried = [actions.get(timeout=5.0) for _ in range(N)]
        # idle after the last cycle, each stage says alone that it is done (the clock's
        # culprit in a stall): every stage's ProcessStats of cycle N - 1 comes
        done: dict[str, int] = {}
        while set(done) != set(PIPELINE) and (msg := alone.get(timeout=5.0)) is not None:
            done[msg.process] = max(done.get(msg.process, -1), msg.env.cycle)
    assert done == dict.fromkeys(PIPELINE, N - 1)
    assert all(r.clean for r in reports)
    # issue 36: each Actions carries its whole pipeline's stats of its cycle
    assert [(m.env.cycle, sorted(m.stats)) for m in carried] == \
        [(t, sorted(PIPELINE)) for t in range(N)]
    assert meanwhile == list(range(N))   # the world's own work of each cycle, once
    assert [r.actions[AGENT] for r in reports] == [(["*pass", t, 1],) for t in range(N)]
    assert set(reports[-1].stage_ms) == set(PIPELINE)
    for process in PIPELINE:
        assert stages.cycles(process) == list(range(N))
