"""How many CPUs this launch may use: the CPUs it may run on (its affinity: taskset, a
container's cpuset), fewer when its control group caps its CPU time (a container's `--cpus`,
a Kubernetes CPU limit). `teleo launch --agents-per-process auto` spreads the agents over
them (tools/launching/run_plan.py `per_core`)."""

from __future__ import annotations

import math
import os
from pathlib import Path

CGROUP = Path("/sys/fs/cgroup")


def usable_cores(cgroup: Path = CGROUP) -> int:
    """The CPUs this process may run on, capped by its control group's CPU quota if any."""
    cores = len(os.sched_getaffinity(0))
    quota = quota_cores(cgroup)
    return max(1, min(cores, quota)) if quota is not None else cores


def quota_cores(cgroup: Path = CGROUP) -> int | None:
    """The control group's CPU quota in whole CPUs (rounded up), or None when there is none or
    it cannot be read: cgroup v2's ``cpu.max`` ("200000 100000": 2 CPUs; "max 100000": none),
    else cgroup v1's ``cpu/cpu.cfs_quota_us`` over ``cpu/cpu.cfs_period_us`` (-1: none)."""
    try:
        return cpus_of(*(cgroup / "cpu.max").read_text().split()[:2])
    except (OSError, TypeError, ValueError):
        pass
    try:
        return cpus_of((cgroup / "cpu" / "cpu.cfs_quota_us").read_text().strip(),
                       (cgroup / "cpu" / "cpu.cfs_period_us").read_text().strip())
    except (OSError, ValueError):
        return None


def cpus_of(quota: str, period: str) -> int | None:
    """Whole CPUs (rounded up) of a quota and period [us]; None for no quota ("max", -1)."""
    if quota == "max" or int(quota) < 0:
        return None
    return max(1, math.ceil(int(quota) / int(period)))
