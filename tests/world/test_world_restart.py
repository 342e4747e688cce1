"""A world that dies comes back exactly where it was (docs/faults.md, "The world dies"):
checkpoints of the real pymunk simulation restore every detail, and `resume` rebuilds the
world from a run folder's checkpoint and trace, refusing one that does not match."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from bus.cycle import CycleReport
from world.domain import Restartable, get_domain
from world.driving.config import CarStart, WorldConfig
from world.driving.simulation import Simulation
from world.errors import WorldError
from world.recorder import CHECKPOINT, TRACE, Recorder
from world.resume import CannotResume, resume
from world.trace import digest

DRIVING = get_domain("driving")
# ME drives into YOU, standing 30 m ahead: the cars touch at about cycle 20 and stay
# touching, so a checkpoint then holds a contact under way
CRASH = (CarStart("ME", "FIRST", "A", "D", along=10.0, speed=10.0),
         CarStart("YOU", "FIRST", "A", "D", along=40.0))
BUSY = {"grid": [4, 4], "pedestrians": 20, "traffic": 4}


def crash_world() -> Simulation:
    return Simulation(WorldConfig(pedestrians=0, traffic=0, cars=CRASH), 1, ["ME", "YOU"])


def digests(world, cycles: int, actions=lambda t: [["*gas", 40]]) -> list[str]:
    out = []
    for t in range(cycles):
        world.apply_actions("ME", actions(t))
        world.step()
        out.append(digest(world.snapshot_dict()))
    return out


def test_a_restored_checkpoint_continues_exactly_as_the_original() -> None:
    world = DRIVING.create(BUSY, 5, ["ME"])
    steer = lambda t: [["*gas", 60], ["*steer", 20 if t % 40 < 20 else -20]]  # noqa: E731
    digests(world, 120, steer)
    again = DRIVING.restore(world.checkpoint())
    assert isinstance(world, Restartable)
    assert digests(again, 300, steer) == digests(world, 300, steer)


def test_a_contact_under_way_at_the_checkpoint_is_not_counted_twice() -> None:
    world = crash_world()
    for _ in range(40):
        world.step()
    assert world.snapshot().counters["ME"]["vehicle_collisions"] == 1  # touching since
    again = DRIVING.restore(world.checkpoint())
    for w in (world, again):
        for _ in range(20):
            w.step()
    assert again.snapshot().counters["ME"]["vehicle_collisions"] == 1
    assert digest(again.snapshot_dict()) == digest(world.snapshot_dict())


def test_restore_refuses_bytes_that_are_not_a_driving_checkpoint() -> None:
    with pytest.raises(WorldError, match="not a driving checkpoint"):
        DRIVING.restore(b"garbage")


def record(folder: Path, cycles: int, seed: int = 5, checkpoint_at: int | None = None,
           prepare=lambda rec, t, snap: None) -> None:
    """What a world process writes for `cycles` cycles with one injected event; `prepare`
    runs where the world process prepares the cycle's record (while the agents work)."""
    world = DRIVING.create(BUSY, seed, ["ME"])
    rec = Recorder(folder, render_every=50)
    outcomes: dict = {"ME": []}
    for t in range(cycles):
        injected = [world.inject({"kind": "pedestrian", "ahead_of": "ME", "dist": 15.0})] \
            if t == 30 else []
        snap = world.snapshot_dict()
        prepare(rec, t, snap)
        applied = {"ME": [["*gas", 50], ["*steer", 5 * ((t // 25) % 3 - 1)]]}
        outcomes = {"ME": world.apply_actions("ME", applied["ME"])}
        world.step()
        rec.cycle(t, snap, applied, injected, CycleReport(t, {"ME": ()}), 0.0)
        if checkpoint_at == t + 1:
            rec.checkpoint(t + 1, world.checkpoint(), outcomes)
    rec.finish(True, 1.0, "done")
    return world, outcomes


@pytest.mark.parametrize("checkpoint_at", [None, 60])
def test_resume_brings_the_world_to_the_first_cycle_not_in_the_trace(tmp_path, checkpoint_at):
    world, outcomes = record(tmp_path, 90, checkpoint_at=checkpoint_at)
    back = resume(DRIVING, BUSY, 5, ["ME"], tmp_path)
    assert back.cycle == 90 and back.outcomes == outcomes
    assert (back.checkpoint, back.replayed) == ((60, 30) if checkpoint_at else (-1, 90))
    assert digest(back.world.snapshot_dict()) == digest(world.snapshot_dict())


def test_a_record_prepared_while_the_agents_work_is_the_same_record(tmp_path):
    plain, prepared, stale = tmp_path / "plain", tmp_path / "prepared", tmp_path / "stale"
    record(plain, 120)
    record(prepared, 120, prepare=lambda rec, t, snap: rec.prepare(t, snap))
    # prepared from another cycle's or another snapshot: not used, the record stays right
    record(stale, 120, prepare=lambda rec, t, snap: rec.prepare(t + 1, snap) if t % 2 else
           rec.prepare(t, dict(snap, counters={})))
    for name in (TRACE, "snapshots.jsonl"):
        want = (plain / name).read_text()
        assert (prepared / name).read_text() == want
        assert (stale / name).read_text() == want


def test_a_partial_last_line_is_ignored_and_cut_before_appending(tmp_path):
    record(tmp_path, 40)
    with (tmp_path / TRACE).open("a") as f:
        f.write('{"cycle": 40, "actio')  # killed while writing
    back = resume(DRIVING, BUSY, 5, ["ME"], tmp_path)
    assert back.cycle == 40
    Recorder(tmp_path, render_every=50, resumed_at=40).trace.close()
    assert (tmp_path / TRACE).read_text().endswith("}\n")


def test_a_trace_that_does_not_match_the_world_cannot_be_resumed(tmp_path):
    record(tmp_path, 40)
    lines = (tmp_path / TRACE).read_text().splitlines()
    doctored = json.loads(lines[25])
    doctored["actions"]["ME"] = [["*brake", 100]]
    lines[25] = json.dumps(doctored)
    (tmp_path / TRACE).write_text("\n".join(lines) + "\n")
    with pytest.raises(CannotResume, match="cycle 26: the replayed state differs"):
        resume(DRIVING, BUSY, 5, ["ME"], tmp_path)


def test_an_unreadable_checkpoint_falls_back_to_replaying_from_cycle_0(tmp_path):
    world, _ = record(tmp_path, 70, checkpoint_at=50)
    (tmp_path / CHECKPOINT).write_bytes(b"\x80\x05truncated")
    back = resume(DRIVING, BUSY, 5, ["ME"], tmp_path)
    assert (back.checkpoint, back.replayed, back.cycle) == (-1, 70, 70)
    assert digest(back.world.snapshot_dict()) == digest(world.snapshot_dict())
