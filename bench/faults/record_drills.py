"""The drills of what a run leaves behind (bench/faults/drills.py runs them; docs/faults.md holds
their figures): its record through a router kill, its files and summary on a disk that
fills, and how long `teleo stop` takes to stop a long run.

- `router-record`: SIGKILL the router at a random cycle; does the record hold every cycle,
  and does the summary's goal history equal the undisturbed run's? (drill N1, docs/faults.md:
  the record once lacked about half the demo's cycles after a router kill);
- `full-disk`: the run folder on a small tmpfs (root only: it mounts one), either left to
  fill or filled at once from outside at a cycle; is the run stopped in order, the summary
  written elsewhere, what it says was lost, the exit code 1? (drill n3_tiny_disk);
- `teleo-stop`: `teleo stop` of a run that has run for a while, timed, with the launcher's
  own parts of the stop from the run's journal (trial #7: 19 s for a 74,211-cycle run);
- `slow-record`: the launcher alone (so its recorder) in a cgroup with a small share of a
  core, its run at full speed beside it: does the record keep every cycle, and how often did
  the world wait for it? (drill d4d: 8,124 of 45,594 cycles lacking with no fault at all;
  root and a cgroup v1 `cpu` hierarchy only).
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import time
from pathlib import Path
from typing import Any

from drill_launch import TELEO, Launch, Reference, pids_alive, wait_for


def drill_router_record(folder: Path, scenario: Path, ref: Reference, at: int
                        ) -> dict[str, Any]:
    """SIGKILL the router when the trace reaches cycle `at`; what the record kept."""
    run = Launch(folder, scenario)
    run.info()
    run.wait_cycle(at)
    base = run.cycles()
    os.kill(run.pid("router"), signal.SIGKILL)
    rc = run.finish()
    s = run.summary()
    return {"drill": "SIGKILL router: the record", "cycle": base, "status": s.get("status"),
            "exit": rc, "identical": run.trace() == ref.trace,
            "record_missing": s.get("record_missing"), "gaps": s.get("record_gaps"),
            "histories_as_undisturbed": histories(s) == histories(ref.summary)}


def histories(summary: dict[str, Any]) -> dict[str, list]:
    return {g["id"]: g.get("history") for g in summary.get("goals", ())}


def drill_full_disk(folder: Path, scenario: Path, size: str, fill_at: int | None
                    ) -> dict[str, Any]:
    """A launch whose TELEO_RUN_DIR is a tmpfs of `size`, filled from outside when the trace
    reaches `fill_at` (None: left to fill by the run), its summary outside it."""
    disk = folder / "disk"
    disk.mkdir()
    mounted = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs",
                              str(disk)], capture_output=True, text=True)
    if mounted.returncode != 0:
        return {"drill": f"full disk {size}", "error": f"cannot mount a tmpfs (root only): "
                                                       f"{mounted.stderr.strip()}"}
    try:
        run = Launch(folder, scenario, "--cycles", "0", runs_in=disk)
        run.info()
        if fill_at is not None:
            run.wait_cycle(fill_at)
            _fill(disk / "filler")
        rc = run.finish()
        s = run.summary()
        return {"drill": f"full disk {size}" + (f", filled at cycle {fill_at}"
                                                if fill_at is not None else ""),
                "cycles": s.get("cycles"), "status": s.get("status"), "exit": rc,
                "summary_written": bool(s),
                "why": (s.get("failures") or [run.output().strip().splitlines()[-1]])[0][:90],
                "record_missing": s.get("record_missing"),
                "record_failed": s.get("record_failed"), "whole": _whole(run),
                "left": len(pids_alive(list(run.info()["pids"].values()))),
                "registered": len(list((disk / "active").glob("*.json")))}
    finally:
        subprocess.run(["umount", "-l", str(disk)], check=False)


def _fill(path: Path) -> None:
    with path.open("wb", buffering=0) as f:  # unbuffered: nothing left to flush on close
        try:
            while True:
                f.write(b"\0" * 65536)
        except OSError:
            pass


def _whole(run: Launch) -> bool:
    """Whether the run's files were closed whole: the world's totals written, the record
    with its summary section and metadata."""
    from mcap.reader import make_reader

    try:
        with (run.run_dir() / "record.mcap").open("rb") as f:
            meta = {m.name for m in make_reader(f).iter_metadata()}
    except Exception:  # noqa: BLE001 (any unreadable record: not whole)
        return False
    return "teleo.run" in meta and (run.run_dir() / "world-final.json").exists()


def drill_teleo_stop(folder: Path, scenario: Path, seconds: float) -> dict[str, Any]:
    """`teleo stop` of a run that has run `seconds`: the command's time, and the launcher's
    parts of the stop (world and stages, the record's drain, the router) from its journal."""
    run = Launch(folder, scenario, "--cycles", "0")
    run.info()
    time.sleep(seconds)
    t0 = time.monotonic()
    done = subprocess.run([TELEO, "stop"], env=run.env, capture_output=True, text=True,
                          timeout=120)
    took = time.monotonic() - t0
    rc = run.finish(60)
    wait_for(lambda: any(e["event"] == "stopped" for e in run.journal()), 5)
    parts = next((e for e in run.journal() if e["event"] == "stopped"), {})
    return {"drill": f"teleo stop after {seconds:g} s", "cycles": run.cycles(),
            "stop_ms": round(took * 1e3), "stop_rc": done.returncode, "exit": rc,
            "launcher_s": parts.get("seconds"),
            **{f"{k}_s": parts.get(k) for k in ("processes", "record", "router")},
            "summary_cycles": run.summary().get("cycles")}


CGROUP_CPU = Path("/sys/fs/cgroup/cpu")


def drill_slow_record(folder: Path, scenario: Path, quota_us: int) -> dict[str, Any]:
    """The launcher in a cgroup of `quota_us` per 100 ms of CPU, every process it starts
    moved out of it at once: a recorder that cannot keep up with its run."""
    group = CGROUP_CPU / f"teleo-drill-{os.getpid()}"
    try:
        group.mkdir(exist_ok=True)
        (group / "cpu.cfs_period_us").write_text("100000")
        (group / "cpu.cfs_quota_us").write_text(str(quota_us))
    except OSError as exc:
        return {"drill": "slow record", "error": f"no cgroup v1 cpu group (root only): {exc}"}

    def enter() -> None:
        (group / "cgroup.procs").write_text(str(os.getpid()))

    try:
        run = Launch(folder, scenario, "--cycles", "3000", preexec_fn=enter)
        while run.proc.poll() is None:
            if list((folder / "active").glob("*.json")):
                run.info()  # read while registered (the run folder is named there)
            for child in _children(run.proc.pid):
                try:
                    (CGROUP_CPU / "cgroup.procs").write_text(str(child))
                except OSError:
                    pass
            time.sleep(0.05)
        rc = run.finish()
    finally:
        group.rmdir()
    s = run.summary()
    health = (run.run_dir() / "health.jsonl").read_text().splitlines()
    waits = [json.loads(x)["seconds"] for x in health if '"record-wait"' in x]
    parts = next((e for e in run.journal() if e["event"] == "stopped"), {})
    return {"drill": f"slow record ({quota_us / 1e3:g} ms of CPU per 100 ms)",
            "cycles": s.get("cycles"), "status": s.get("status"), "exit": rc,
            "record_missing": s.get("record_missing"), "gaps": s.get("record_gaps"),
            "waits": len(waits), "waited_s": round(sum(waits), 1),
            "cycles_per_s": s.get("cycles_per_s"), "drain_s": parts.get("record")}


def _children(pid: int) -> list[int]:
    out = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            out += [int(c) for c in (task / "children").read_text().split()]
        except OSError:
            continue
    return out
