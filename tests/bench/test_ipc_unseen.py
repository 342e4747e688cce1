"""Domains teleo was not tuned on (bench/ipc/unseen: zenotravel, transport, parcprinter, tpp,
depot, elevators, scanalyzer, as distributed with pyperplan): `teleo solve` runs each end to
end in a real subprocess and ends with a status, a plan the independent replay
(bench/ipc/strips.py) accepts when it says achieved, and a reason when it does not; the IPC
bench takes such a folder with --suites (a domain file per task, as parcprinter's) and leaves
out runs with --planners, --no-learned."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from bench.ipc import strips

ROOT = Path(__file__).resolve().parents[2]
UNSEEN = ROOT / "bench" / "ipc" / "unseen"
TELEO = Path(sys.executable).parent / "teleo"
BENCH = ROOT / "bench" / "ipc" / "ipc.py"


def files(domain: str, task: int) -> tuple[Path, Path]:
    own = UNSEEN / domain / f"domain{task:02d}.pddl"
    return (own if own.exists() else UNSEEN / domain / "domain.pddl",
            UNSEEN / domain / f"task{task:02d}.pddl")


def solved(domain: str, task: int, *more: str) -> dict:
    """`teleo solve --json` of an unseen task (``more``: further options), checked: a status
    and a reason, and no success the independent replay denies."""
    dom, prob = files(domain, task)
    done = subprocess.run([str(TELEO), "solve", str(dom), str(prob), "--json", *more],
                          capture_output=True, text=True, timeout=240, cwd=ROOT)
    assert "Traceback" not in done.stderr, done.stderr
    data = json.loads(done.stdout)
    assert done.returncode == (0 if data["status"] == "achieved" else 1)
    assert data["status"] in ("achieved", "failed", "limit")
    verdict = strips.check(strips.load(dom, prob), data["actions"])
    if data["status"] == "achieved":
        assert verdict.valid, verdict.reason   # never a success the replay denies
    else:
        assert data["reason"].strip(), data   # never an end without a reason
    return data


def test_every_unseen_suite_holds_five_tasks_pyperplan_reads():
    for domain in ("zenotravel", "transport", "parcprinter", "tpp", "depot", "elevators",
                   "scanalyzer"):
        for task in range(1, 6):
            t = strips.load(*files(domain, task))
            assert t.goal and t.operators, (domain, task)


@pytest.mark.parametrize("domain,task", [("zenotravel", 2), ("zenotravel", 3),
                                         ("parcprinter", 1), ("parcprinter", 2),
                                         ("transport", 1)])
def test_teleo_solves_unseen_tasks_with_plans_the_replay_accepts(domain, task):
    data = solved(domain, task)
    assert data["status"] == "achieved" and data["actions"]


@pytest.mark.parametrize("task", [1, 3])
def test_a_skill_whose_static_percepts_bind_two_variables_to_one_object_applies(task):
    # TPP's goal (stored goods1 level1) has one way: (unload goods1 truck1 depot1 level0
    # level1 level0 level1), the two (next ?a ?b) percepts fixing the level pairs alike;
    # keeping each variable's object apart left stored with no primitive skill that applies
    data = solved("tpp", task)
    assert data["status"] == "achieved", data["reason"]
    assert ["unload", "goods1", "truck1", "depot1", "level0", "level1", "level0",
            "level1"] in data["actions"]


def test_depot_loads_the_crate_where_it_lies_before_driving_the_truck_to_unload_it(tmp_path):
    # depot task01: crate1 lies at depot0 and is to go on pallet1 at distributor0. Two
    # defects made it circle: ordering the unloading's start, the regression of (in crate1
    # truck0) went back through the hoist lifting it at the distributor (the very goal the
    # unloading is for), so the truck drove there first; and the skill learned for loading
    # crate0 left out that the crate must be where it is loaded (kept now because the
    # domain's stated effects show the truck's drive leaves it alone; blocks, whose skills
    # state no effects, keeps its shorter learned starts: tests/lang/solving/test_conjunction)
    learned = tmp_path / "depot.lrn"
    data = solved("depot", 1, "--learned-out", str(learned))
    assert data["status"] == "achieved", data["reason"]
    acts = data["actions"]
    assert acts.index(["load", "hoist0", "crate1", "truck0", "depot0"]) < \
        acts.index(["unload", "hoist1", "crate1", "truck0", "distributor0"])
    text = learned.read_text()
    loading = text[text.index("((in ?o1 ?o2)"):].split("\n\n")[0]
    assert "(at ?o1 ?o3)" in loading and "(lifting ?o4 ?o1)" in loading


def test_elevators_learned_boarding_and_leaving_keep_the_lift_count(tmp_path):
    # elevators task03: the passenger counts are objects of the same type as the floors
    # (n0 n1 ...), so a way to board at floor n1 with the lift empty names n1 twice; keeping
    # each variable's object apart left it out. The skills learned for boarding and leaving
    # keep the lift's count in their start (any leave changes the count, which made the
    # learner drop it as excluded by the passenger's place)
    learned = tmp_path / "elevators.lrn"
    data = solved("elevators", 3, "--learned-out", str(learned))
    assert data["status"] == "achieved", data["reason"]
    text = learned.read_text()
    skills = [part for part in text.split("\n\n") if "((boarded ?o1 ?o2)" in part or
              "((passenger-at ?o1 ?o2)" in part]
    assert len(skills) >= 2 and all("(passengers ?o" in part for part in skills)


@pytest.mark.parametrize("domain,task", [("elevators", 1), ("elevators", 5),
                                         ("scanalyzer", 1), ("scanalyzer", 2)])
def test_elevators_and_scanalyzer_tasks_are_solved_with_plans_the_replay_accepts(domain,
                                                                                  task):
    # elevators circled (a passenger boarded and left again at the same floor, for a count
    # the lift had when the way was chosen) and scanalyzer undid the rotation the way under
    # way had just made (a conjunct one action achieves was done in passing); tuned on
    # neither
    data = solved(domain, task)
    assert data["status"] == "achieved", data["reason"]


@pytest.mark.parametrize("domain,task", [("transport", 2), ("transport", 3)])
def test_a_run_that_does_not_solve_ends_with_a_status_and_its_reason(domain, task):
    data = solved(domain, task)   # achieved and valid, or failed/limit with its reason
    assert data["status"] == "achieved" or data["goal"] in data["reason"] or \
        "cycles ran out" in data["reason"]


def test_the_bench_runs_a_suite_folder_with_a_domain_file_per_task(tmp_path):
    done = subprocess.run([sys.executable, str(BENCH), "--suites", str(UNSEEN), "--domains",
                           "parcprinter", "--tasks", "2", "--planners", "gbf-hff",
                           "--no-learned", "--no-cross", "--jobs", "1", "--limit", "120",
                           "--keep", str(tmp_path)],
                          capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    row = next(line.split() for line in done.stdout.splitlines() if line.startswith("task02"))
    # teleo fresh solved (length, ratio, cycles, solving cycles, time); no learned or cross
    # run; gbf+hff solved; astar+lmcut not run
    assert row[2] == "x1.00" and row[6:8] == ["-", "-"] and row[9] == "x1.00"
    assert row[11] == "-"
    summary = next(line.split() for line in done.stdout.splitlines()
                   if line.startswith("parcprinter "))
    assert summary[1:6] == ["1/1", "-", "-", "1/1", "-"]
    assert (tmp_path / "parcprinter-task02-gbf-hff" / "domain.pddl").read_text() == \
        (UNSEEN / "parcprinter" / "domain02.pddl").read_text()


@pytest.mark.parametrize("args,hint", [
    (["--suites", "bench"], "--suites"),
    (["--suites", "bench/ipc/unseen", "--domains", "blocks"], "--domains"),
    (["--planners", "astar-blind"], "--planners"),
])
def test_bad_suite_options_are_one_usage_error(args, hint):
    done = subprocess.run([sys.executable, str(BENCH), *args], capture_output=True, text=True,
                          timeout=60, cwd=ROOT)
    assert done.returncode == 2 and hint in done.stderr, done.stderr
    assert "Traceback" not in done.stderr and done.stdout == ""
