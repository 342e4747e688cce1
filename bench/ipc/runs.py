"""One run of one IPC task (issue 35): teleo (`teleo solve DOMAIN PROBLEM --json` in a
subprocess killed at the time limit, fresh or with learned skills) or pyperplan (`python -m
pyperplan` likewise, gbf+hff or astar+lmcut), each plan replayed by bench/ipc/strips.py.

Both functions run in a worker process of bench/ipc/ipc.py's pool and return plain data.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from bench.ipc import strips

ROOT = Path(__file__).resolve().parents[2]
TELEO = Path(sys.executable).parent / "teleo"
PLANNERS = {"gbf-hff": ("gbf", "hff"), "astar-lmcut": ("astar", "lmcut")}
START_S = 3.0   # the interpreter's start and teleo's import, left out of teleo's own limit [s]
EXPANDED = re.compile(r"(\d+) Nodes expanded")


@dataclass(frozen=True)
class Run:
    """One run's figures. ``who``: teleo-fresh, teleo-learned, teleo-cross (with the skills of
    another task, ``source``), gbf-hff or astar-lmcut. ``status``: solved, failed (the run ended
    with the goal unachieved; ``detail`` its reason), limit (teleo's cycle or time limit),
    timeout (killed at the time limit), invalid (teleo claimed the goal achieved, the replay
    denies it; ``detail`` why) or error. ``claimed``: teleo's summary said achieved. ``length`` in
    actions, ``cycles`` and ``solving`` (problem-solving cycles) teleo's, ``wall_s`` [s]
    including the interpreter's start, ``solve_s`` [s] teleo's own time for the run (its
    ``elapsed_s``, without the start of the interpreter and the import of teleo);
    ``learned``: the file of the skills the run learned (teleo), ``plan``: the actions."""

    domain: str
    task: str
    who: str
    status: str
    claimed: bool = False
    length: int = 0
    cycles: int = 0
    solving: int = 0
    learned_count: int = 0
    wall_s: float = 0.0
    solve_s: float = 0.0
    detail: str = ""
    learned: str = ""
    source: str = ""
    plan: tuple[tuple[str, ...], ...] = ()

    @property
    def solved(self) -> bool:
        return self.status == "solved"


def _reason(data: dict) -> str:
    """The reason a teleo summary gives for a goal it did not achieve ("" if none)."""
    for key in ("reason", "why", "failed"):
        if isinstance(data.get(key), str) and data[key].strip():
            return data[key].strip()
    for goal in data.get("goals", ()) or ():
        if isinstance(goal, dict):
            for key in ("reason", "why", "failed", "note"):
                if isinstance(goal.get(key), str) and goal[key].strip():
                    return goal[key].strip()
    return ""


def run_teleo(domain: str, task: str, domain_file: str, problem_file: str, limit_s: float,
              folder: str, who: str = "teleo-fresh", learned_in: str = "",
              source: str = "", cycles: int = 0) -> Run:
    """Solve the task with `teleo solve --time-limit` (``limit_s`` less START_S, so that it
    ends itself with status limit and its reason), killed after ``limit_s`` [s]; the skills
    it learns go to a file under ``folder``; ``learned_in``: a file of skills learned
    before."""
    out = Path(folder) / f"{domain}-{task}-{who}{'-' + source if source else ''}.tlp"
    out.unlink(missing_ok=True)
    cmd = [str(TELEO), "solve", domain_file, problem_file, "--json", "--learned-out", str(out),
           "--time-limit", f"{max(1.0, limit_s - START_S):g}"]
    if learned_in:
        cmd += ["--learned", learned_in]
    if cycles:
        cmd += ["--cycles", str(cycles)]
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=limit_s, cwd=ROOT)
    except subprocess.TimeoutExpired:
        return Run(domain, task, who, "timeout", wall_s=time.perf_counter() - start,
                   source=source, detail=f"killed at {limit_s:g} s")
    wall = time.perf_counter() - start
    try:
        data = json.loads(done.stdout)
    except json.JSONDecodeError:
        tail = (done.stderr.strip().splitlines() or done.stdout.strip().splitlines()
                or [f"exit {done.returncode}"])[-1]
        return Run(domain, task, who, "error", wall_s=wall, detail=tail[:300], source=source)
    plan = tuple(tuple(str(x).lower() for x in a) for a in data.get("actions", ()))
    status = str(data.get("status", ""))
    learned = data.get("learned", ())
    common = dict(claimed=status == "achieved", length=len(plan),
                  cycles=int(data.get("cycles", 0)), solving=int(data.get("solving_cycles", 0)),
                  learned_count=len(learned) if isinstance(learned, list) else int(learned or 0),
                  wall_s=wall, solve_s=float(data.get("elapsed_s", 0.0) or 0.0),
                  learned=str(out) if out.exists() else "", source=source,
                  plan=plan)
    if status == "achieved":
        verdict = strips.verify(domain_file, problem_file, plan)
        if not verdict.valid:
            return Run(domain, task, who, "invalid" if verdict.read else "unchecked",
                       detail=verdict.reason, **common)
        return Run(domain, task, who, "solved", **common)
    return Run(domain, task, who, status if status in ("failed", "limit") else "error",
               detail=_reason(data) or (f"exit {done.returncode}, status {status!r}"
                                        if status not in ("failed", "limit") else ""),
               **common)


def run_pyperplan(domain: str, task: str, domain_file: str, problem_file: str, planner: str,
                  limit_s: float, folder: str) -> Run:
    """Solve the task with pyperplan's ``planner`` within ``limit_s`` [s] (files copied under
    ``folder``, where pyperplan writes its .soln, without any action costs: pyperplan runs
    none), its plan replayed like teleo's."""
    search, heuristic = PLANNERS[planner]
    here = Path(folder) / f"{domain}-{task}-{planner}"
    here.mkdir(parents=True, exist_ok=True)
    dom, prob = here / "domain.pddl", here / "problem.pddl"
    for src, dst in ((domain_file, dom), (problem_file, prob)):   # pyperplan runs no costs
        text = Path(src).read_text()
        dst.write_text(strips.uncosted(text) if strips.has_costs(text) else text)
    soln = here / "problem.pddl.soln"
    soln.unlink(missing_ok=True)
    cmd = [sys.executable, "-m", "pyperplan", "-s", search, "-H", heuristic, str(dom), str(prob)]
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=limit_s)
    except subprocess.TimeoutExpired:
        return Run(domain, task, planner, "timeout", wall_s=time.perf_counter() - start,
                   detail=f"killed at {limit_s:g} s")
    wall = time.perf_counter() - start
    if done.returncode != 0:
        last = (done.stdout + done.stderr).strip().splitlines()[-1:] or [
            f"exit {done.returncode}"]
        return Run(domain, task, planner, "error", wall_s=wall, detail=last[0][:300])
    if not soln.exists():
        return Run(domain, task, planner, "failed", wall_s=wall, detail="no plan found")
    plan = tuple(strips.read_plan(soln.read_text()))
    verdict = strips.verify(domain_file, problem_file, plan)
    if not verdict.valid:
        return Run(domain, task, planner, "invalid" if verdict.read else "unchecked", True,
                   len(plan), wall_s=wall, detail=verdict.reason, plan=plan)
    return Run(domain, task, planner, "solved", True, len(plan), wall_s=wall, plan=plan)
