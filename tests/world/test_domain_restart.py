"""Every registered domain can be brought back by a restarted world process (docs/faults.md,
"A world's restart"): from its checkpoint when it offers one, else by replaying the run from
cycle 0. The world written down by the recorder and the one `resume` rebuilds are the same."""

from __future__ import annotations

import pytest

from bus.cycle import CycleReport
from world.domain import DOMAINS, Restartable, get_domain
from world.recorder import Recorder
from world.resume import resume
from world.trace import digest


@pytest.mark.parametrize("name", DOMAINS)
def test_a_restarted_world_of_every_domain_is_the_world_that_died(name, tmp_path):
    domain = get_domain(name)
    world = domain.create({}, 4, ["ME"])
    rec = Recorder(tmp_path, render_every=100)
    saves = isinstance(world, Restartable) and domain.restore is not None
    for t in range(60):
        snap = world.snapshot_dict()
        applied = {"ME": world.safe_actions("ME")}
        outcomes = {"ME": world.apply_actions("ME", applied["ME"])}
        world.step()
        rec.cycle(t, snap, applied, [], CycleReport(t, {"ME": ()}), 0.0)
        if saves and t + 1 == 40:
            rec.checkpoint(40, world.checkpoint(), outcomes)
    rec.finish(True, 1.0, "done")
    back = resume(domain, {}, 4, ["ME"], tmp_path)
    assert (back.cycle, back.checkpoint) == (60, 40 if saves else -1)
    assert back.outcomes == outcomes
    assert digest(back.world.snapshot_dict()) == digest(world.snapshot_dict())
