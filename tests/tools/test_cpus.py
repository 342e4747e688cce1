"""How many CPUs `--agents-per-process auto` spreads the agents over (tools/launching/cpus.py): the
CPUs the launch may run on, fewer when its control group caps its CPU time, as a container's
`--cpus 2` or a Kubernetes CPU limit does (cgroup v2 and v1 layouts, written into a folder)."""

from __future__ import annotations

import os

import pytest

from tools.launching.cpus import cpus_of, quota_cores, usable_cores


def cgroup_v2(tmp_path, cpu_max: str):
    (tmp_path / "cpu.max").write_text(cpu_max + "\n")
    return tmp_path


def cgroup_v1(tmp_path, quota: str, period: str = "100000"):
    (tmp_path / "cpu").mkdir()
    (tmp_path / "cpu" / "cpu.cfs_quota_us").write_text(quota + "\n")
    (tmp_path / "cpu" / "cpu.cfs_period_us").write_text(period + "\n")
    return tmp_path


@pytest.mark.parametrize("quota, period, cpus", [
    ("200000", "100000", 2), ("150000", "100000", 2), ("50000", "100000", 1),
    ("1600000", "100000", 16), ("max", "100000", None), ("-1", "100000", None)])
def test_a_quota_counts_whole_cpus_rounded_up(quota, period, cpus):
    assert cpus_of(quota, period) == cpus


def test_cgroup_v2_cpu_max_caps_the_cpus(tmp_path):
    assert quota_cores(cgroup_v2(tmp_path, "100000 100000")) == 1
    assert usable_cores(tmp_path) == 1


def test_cgroup_v2_without_a_limit_leaves_the_affinity(tmp_path):
    assert quota_cores(cgroup_v2(tmp_path, "max 100000")) is None
    assert usable_cores(tmp_path) == len(os.sched_getaffinity(0))


def test_cgroup_v1_quota_caps_the_cpus(tmp_path):
    assert quota_cores(cgroup_v1(tmp_path, "100000")) == 1
    assert usable_cores(tmp_path) == 1


def test_cgroup_v1_without_a_quota_or_no_cgroup_at_all_leaves_the_affinity(tmp_path):
    assert quota_cores(tmp_path) is None   # nothing there to read
    assert quota_cores(cgroup_v1(tmp_path, "-1")) is None
    assert usable_cores(tmp_path) == len(os.sched_getaffinity(0))


def test_a_quota_above_the_affinity_leaves_the_affinity(tmp_path):
    assert usable_cores(cgroup_v2(tmp_path, "6400000 100000")) == len(os.sched_getaffinity(0))


def test_a_garbled_cpu_max_is_no_limit(tmp_path):
    assert quota_cores(cgroup_v2(tmp_path, "lots")) is None
