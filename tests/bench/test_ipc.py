"""bench/ipc: the independent STRIPS replay (bench/ipc/strips.py) on known-good and known-bad
plans of the vendored IPC tasks, and the bench end to end on one tiny task (real teleo and
pyperplan subprocesses)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from bench.ipc import strips

ROOT = Path(__file__).resolve().parents[2]
SUITES = ROOT / "bench" / "ipc" / "suites"


def task(domain: str, number: int = 1) -> strips.StripsTask:
    return strips.load(SUITES / domain / "domain.pddl", SUITES / domain / f"task{number:02d}.pddl")


def test_every_vendored_suite_parses_with_its_tasks():
    for domain in ("blocks", "gripper", "logistics", "miconic", "movie"):
        tasks = sorted((SUITES / domain).glob("task*.pddl"))
        assert len(tasks) >= 20, domain
        t = task(domain)
        assert t.init and t.goal and t.operators


def test_a_known_good_plan_replays_to_the_goal():
    # blocks task01: a b c d on the table; goal d on c on b on a
    t = task("blocks")
    assert {("ontable", b) for b in "abcd"} <= t.init
    good = [("pick-up", "b"), ("stack", "b", "a"), ("pick-up", "c"), ("stack", "c", "b"),
            ("pick-up", "d"), ("stack", "d", "c")]
    assert t.goal == {("on", "b", "a"), ("on", "c", "b"), ("on", "d", "c")}
    assert strips.check(t, good) == strips.Verdict(True, 6)


def test_gripper_good_plan_and_typing_of_untyped_domains():
    t = task("gripper")
    balls = sorted(a[1] for a in t.goal)
    plan = []
    for ball in balls:
        plan += [("pick", ball, "rooma", "left"), ("move", "rooma", "roomb"),
                 ("drop", ball, "roomb", "left"), ("move", "roomb", "rooma")]
    assert strips.check(t, plan).valid


@pytest.mark.parametrize("plan,reason", [
    ([("stack", "b", "a")], "step 1: (stack b a): precondition (holding b) is false"),
    ([("pick-up", "b"), ("pick-up", "c")],
     "step 2: (pick-up c): precondition (handempty) is false"),
    ([("fly", "b")], "step 1: (fly b): no operator fly"),
    ([("pick-up", "b", "a")], "step 1: (pick-up b a): pick-up takes 1 arguments, got 2"),
    ([("pick-up", "z")], "step 1: (pick-up z): z is no object of the problem"),
    ([("pick-up", "b")], "the goal's (on b a) (on c b) (on d c) false at the end"),
])
def test_a_known_bad_plan_is_denied_naming_the_step_and_literal(plan, reason):
    verdict = strips.check(task("blocks"), plan)
    assert not verdict.valid
    assert verdict.reason.startswith(reason)


def test_a_typed_domain_refuses_an_object_of_the_wrong_type():
    t = task("logistics")
    truck = next(o for o, kinds in t.kinds.items() if "truck" in kinds)
    package = next(o for o, kinds in t.kinds.items() if "package" in kinds)
    where = next(a[2] for a in t.init if a[0] == "at" and a[1] == truck)
    verdict = strips.check(t, [("load-truck", truck, package, where)])
    assert not verdict.valid and "is not of type package" in verdict.reason


def test_pyperplans_plan_file_reads_back_as_steps():
    assert strips.read_plan("(pick-up b)\n(stack b a)\n; cost = 2\n") == [
        ("pick-up", "b"), ("stack", "b", "a")]


def test_bad_options_are_one_usage_error_without_a_traceback():
    for args, hint in ((["--tasks", "x"], "--tasks"), (["--domains", "nope"], "--domains"),
                       (["--jobs", "3"], "--jobs")):
        done = subprocess.run([sys.executable, str(ROOT / "bench" / "ipc" / "ipc.py"), *args],
                              capture_output=True, text=True, timeout=60, cwd=ROOT)
        assert done.returncode == 2 and hint in done.stderr
        assert "Traceback" not in done.stderr and done.stdout == ""


def test_quick_on_one_tiny_task_prints_the_tables_and_every_target(tmp_path):
    done = subprocess.run([sys.executable, str(ROOT / "bench" / "ipc" / "ipc.py"), "--quick",
                           "--domains", "movie", "--tasks", "1", "--jobs", "1", "--keep",
                           str(tmp_path)], capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    out = done.stdout
    row = next(line.split() for line in out.splitlines() if line.startswith("task01"))
    # teleo fresh and learned, no cross run (one task), gbf+hff and astar+lmcut: each 7 steps,
    # the best plan, replayed by bench/ipc/strips.py
    assert row[1:5] == ["7", "x1.00", "c8", "s0"] and row[6:10] == ["7", "x1.00", "c8", "s0"]
    assert row[11] == "-" and row[12:14] == ["7", "x1.00"] and row[15:17] == ["7", "x1.00"]
    summary = next(line.split() for line in out.splitlines() if line.startswith("movie "))
    assert summary[1:6] == ["1/1", "1/1", "-", "1/1", "1/1"]
    targets = [line for line in out.splitlines() if line.startswith("  [")]
    assert len(targets) == 6 and all(t.startswith("  [met]") for t in targets)
    assert (tmp_path / "movie-task01-teleo-fresh.tlp").exists()
    assert (tmp_path / "movie-task01-gbf-hff" / "problem.pddl.soln").exists()
