"""A run whose disk fills (issue 24, item 4; drill n3_tiny_disk: on a 2 MB tmpfs the world
died at cycle 1500 with an ENOSPC traceback and the launcher exited with one line and no
summary). Now the launcher stops the run in order while every file can still be closed
whole; a disk filled at once stops the world at the cycle it could not record; either way
the summary is written where there is room, says what the record and the trace hold, the
exit code says the run failed, and nothing is left running or registered.

The disk is a real small tmpfs (root, as CI runs); elsewhere each file is limited in size
instead (RLIMIT_FSIZE: every write past it fails, with EFBIG), the nearest equivalent."""

from __future__ import annotations

import json
import os
import resource
import subprocess
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest
from e2e_helpers import ROOT, TELEO, wait_for
from fault_helpers import pids_alive, scenario

from tools.records.run_record import RunRecord

SIZE = "2m"             # the tmpfs
FILE_LIMIT = 300_000    # [bytes] each file, where no tmpfs can be mounted


@dataclass
class Disk:
    folder: Path
    tmpfs: bool

    def launch(self, tmp_path: Path, *args: str) -> subprocess.Popen:
        """`teleo launch` with its run folder (TELEO_RUN_DIR) on this disk and its summary
        beside the test, on a disk with room."""
        def limit() -> None:
            if not self.tmpfs:
                resource.setrlimit(resource.RLIMIT_FSIZE, (FILE_LIMIT, FILE_LIMIT))
        out = (tmp_path / "launch.out").open("w")
        return subprocess.Popen(
            [*TELEO, "launch", str(scenario(tmp_path)), "--summary",
             str(tmp_path / "summary.json"), *args], cwd=ROOT,
            env={**os.environ, "TELEO_RUN_DIR": str(self.folder)}, stdout=out,
            stderr=subprocess.STDOUT, preexec_fn=limit)  # noqa: PLW1509 (no threads here)

    def fill(self) -> None:
        """Take every byte left (tmpfs; with a size limit the limit does it)."""
        if self.tmpfs:
            # unbuffered: nothing is left to flush (and fail) when it closes
            with (self.folder / "filler").open("wb", buffering=0) as f:
                try:
                    while True:
                        f.write(b"\0" * 65536)
                except OSError:
                    pass


@pytest.fixture
def disk(tmp_path) -> Iterator[Disk]:
    folder = tmp_path / "disk"
    folder.mkdir()
    mounted = os.geteuid() == 0 and subprocess.run(
        ["mount", "-t", "tmpfs", "-o", f"size={SIZE}", "tmpfs", str(folder)],
        capture_output=True).returncode == 0
    try:
        yield Disk(folder, mounted)
    finally:
        if mounted:
            subprocess.run(["umount", "-l", str(folder)], check=True)


def run_dir(disk: Disk) -> Path:
    return next((disk.folder / "runs").iterdir())


def trace_cycles(disk: Disk) -> int:
    path = run_dir(disk) / "trace.jsonl"
    return path.read_bytes().count(b"\n") if path.exists() else 0


def ended_in_order(disk: Disk, tmp_path: Path, launcher: subprocess.Popen) -> dict:
    """What every stop on a full disk must show; the summary."""
    out = (tmp_path / "launch.out").read_text()
    assert launcher.wait(120) == 1, out
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["status"] == "failed" and s["failures"], out
    assert s["cycles"] == trace_cycles(disk)    # the summary counts what the trace holds
    assert "Traceback" not in out and "Error: No space left" not in out
    for log in (run_dir(disk) / "logs").glob("*.log"):
        assert "Traceback" not in log.read_text(errors="replace"), log.name
    assert not list((disk.folder / "active").glob("*.json"))  # unregistered
    assert wait_for(lambda: processes_of(s["run"]) == [], 10), processes_of(s["run"])
    return s


def processes_of(run: str) -> list[int]:
    """The live processes whose command line names `run` (every process of a run does)."""
    found = []
    for proc in Path("/proc").iterdir():
        if proc.name.isdigit():
            try:
                if run in (proc / "cmdline").read_bytes().decode(errors="replace"):
                    found.append(int(proc.name))
            except OSError:
                continue
    return pids_alive(found)


def test_a_run_on_a_small_disk_stops_in_order_with_its_summary_written_elsewhere(disk,
                                                                                tmp_path):
    launcher = disk.launch(tmp_path, "--cycles", "20000")
    s = ended_in_order(disk, tmp_path, launcher)
    if disk.tmpfs:  # stopped by the launcher while there was room: every file is whole
        [reason] = s["failures"]
        assert reason.startswith(f"the run was stopped: its folder {run_dir(disk)} is on a "
                                 "file system that is nearly full (")
        assert s["record_missing"] == 0 and s["record_failed"] is None
        held = int(RunRecord(Path(s["record"])).meta["teleo.run"]["world_states"])
        assert held in (s["cycles"], s["cycles"] + 1)  # closed whole, with its metadata (the
        #                                   state of a cycle the stop cut short may be in it)
        final = json.loads((run_dir(disk) / "world-final.json").read_text())
        assert final["cycles"] == s["cycles"] and final["lost"] == {}
    else:           # each file capped: the first one past it is named, the run stopped
        assert any("could not" in f for f in s["failures"]), s["failures"]


def test_a_disk_filled_at_once_stops_the_world_and_the_summary_says_what_was_lost(disk,
                                                                                 tmp_path):
    launcher = disk.launch(tmp_path, "--cycles", "20000")
    assert wait_for(lambda: (disk.folder / "runs").exists() and trace_cycles(disk) >= 150
                    or launcher.poll() is not None, 120)
    disk.fill()
    s = ended_in_order(disk, tmp_path, launcher)
    world = [f for f in s["failures"] if f.startswith("the world stopped at cycle")]
    guard = [f for f in s["failures"] if "is nearly full" in f]
    assert world or guard, s["failures"]       # the world, or the launcher's look, first
    if world:
        assert world[0].startswith(f"the world stopped at cycle {s['cycles']}: it could not "
                                   f"write its files in {run_dir(disk)} (")
    if s["record_failed"]:                     # and which cycles the record lacks
        lost = next(f for f in s["failures"] if f.startswith("the run record"))
        assert "could not be written (" in lost and (
            "it lacks cycles" in lost or "nothing was written from about cycle" in lost)
        assert s["record_missing"] is None or s["record_missing"] > 0
