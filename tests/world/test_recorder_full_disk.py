"""A world whose run folder cannot be written (issue 24, item 4; drill N3b: the world died at
cycle 1500 with an ENOSPC traceback in `checkpoint`): the trace or the health record that
cannot be written stops it with CannotRecord, naming the file and the cycle; a snapshot or a
checkpoint that cannot be written is given up and the run goes on; `finish` never raises.
The full disk is real: the file is a link to /dev/full, whose every write fails with ENOSPC."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from bus.cycle import CycleReport
from world.domain import get_domain
from world.errors import CannotRecord
from world.recorder import CHECKPOINT, HEALTH, SNAPSHOTS, TRACE, WORLD_FINAL, Recorder
from world.run_scenario import load_scenario

ROOT = Path(__file__).resolve().parents[2]
DEMO = load_scenario(ROOT / "scenarios" / "driving_demo.toml")


def full(folder: Path, *names: str) -> None:
    """Make each of `names` in `folder` a file on a full disk."""
    folder.mkdir(parents=True, exist_ok=True)
    for name in names:
        (folder / name).symlink_to("/dev/full")


def run(rec: Recorder, cycles: int) -> int:
    """Record up to `cycles` cycles of the demo's world (a checkpoint every 10); the cycles
    recorded before CannotRecord, if it came."""
    domain = get_domain(DEMO.domain)
    world = domain.create(DEMO.world_table, 7, DEMO.agent_ids)
    for t in range(cycles):
        snap = world.snapshot_dict()
        applied = {"ME": [["*gas", 30]]}
        outcomes = {"ME": world.apply_actions("ME", applied["ME"])}
        world.step()
        try:
            rec.cycle(t, snap, applied, [], CycleReport(t, {"ME": ()}), 0.0)
        except CannotRecord:
            return t
        if (t + 1) % 10 == 0:
            rec.checkpoint(t + 1, world.checkpoint(), outcomes)
    return cycles


def test_a_trace_that_cannot_be_written_stops_the_world_at_that_cycle(tmp_path) -> None:
    full(tmp_path, TRACE)
    rec = Recorder(tmp_path, render_every=1)
    with pytest.raises(CannotRecord, match=r"trace.jsonl: cycle 0 cannot be written "
                                           r"\(No space left on device\)"):
        rec.cycle(0, {"counters": {}}, {}, [], CycleReport(0, {}), 0.0)
    rec.finish(False, 0.1, "stopped")  # never raises: the rest is written where it can be
    final = json.loads((tmp_path / WORLD_FINAL).read_text())
    assert final["cycles"] == 0 and final["reason"] == "stopped"


def test_a_health_record_that_cannot_be_written_stops_it_too(tmp_path) -> None:
    """The summary counts uncontrolled cycles from it: a run must not go on without it."""
    full(tmp_path, HEALTH)
    with pytest.raises(CannotRecord, match="health.jsonl"):
        Recorder(tmp_path, render_every=1).event("start", cycle=0)


def test_snapshots_and_checkpoints_are_given_up_and_the_run_goes_on(tmp_path) -> None:
    full(tmp_path, SNAPSHOTS, CHECKPOINT + ".tmp")
    rec = Recorder(tmp_path, render_every=1)
    assert run(rec, 40) == 40
    assert rec.lost[CHECKPOINT] == {"cycle": 10, "reason": "No space left on device"}
    assert rec.lost[SNAPSHOTS]["reason"] == "No space left on device"
    assert rec.lost[SNAPSHOTS]["cycle"] < 40
    assert not (tmp_path / (CHECKPOINT + ".tmp")).exists()  # its own half file: removed
    assert not (tmp_path / CHECKPOINT).exists()
    rec.finish(True, 1.0, "done")
    assert len((tmp_path / TRACE).read_text().splitlines()) == 40
    final = json.loads((tmp_path / WORLD_FINAL).read_text())
    assert final["lost"] == rec.lost and final["cycles"] == 40
    end = json.loads((tmp_path / HEALTH).read_text().splitlines()[-1])
    assert end["kind"] == "end" and end["lost"] == rec.lost


def test_a_run_folder_that_cannot_be_opened_is_cannot_record(tmp_path) -> None:
    full(tmp_path, SNAPSHOTS)
    os.chmod(tmp_path, 0o500)
    try:
        if os.access(tmp_path, os.W_OK):  # root writes anyway: a file in the way, then
            os.chmod(tmp_path, 0o700)
            (tmp_path / TRACE).mkdir()
        with pytest.raises(CannotRecord, match="cannot be opened for writing"):
            Recorder(tmp_path, render_every=1)
    finally:
        os.chmod(tmp_path, 0o700)
