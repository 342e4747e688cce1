"""pyperplan on a Blocks World problem: the PDDL of bench/planning/bw_pddl.py solved by `python -m
pyperplan` in a subprocess killed at its time limit (so a stuck search cannot hang the bench),
the plan read back from the .soln file pyperplan writes and checked under STRIPS rules
(bench/planning/bw_strips.py) like teleo's.

PLANNERS: ``gbf-hff`` greedy best-first search with the FF heuristic, ``astar-lmcut`` A* with
LM-cut (admissible: its plans are optimal).
"""

from __future__ import annotations

import re
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from bench.planning import bw_strips
from bench.planning.bw_pddl import DOMAIN, plan_steps, problem_pddl
from bench.planning.bw_problems import Problem

PLANNERS = {"gbf-hff": ("gbf", "hff"), "astar-lmcut": ("astar", "lmcut")}
EXPANDED = re.compile(r"(\d+) Nodes expanded")


@dataclass(frozen=True)
class PlanResult:
    """``status``: solved, timeout (killed at the limit), unsolved (the search ended with no
    plan) or error (with ``detail``); ``length`` in actions; ``expanded`` search nodes;
    ``wall_s`` [s] including the interpreter's start."""

    planner: str
    status: str
    length: int = 0
    expanded: int = 0
    wall_s: float = 0.0
    detail: str = ""

    @property
    def solved(self) -> bool:
        return self.status == "solved"


def run_pyperplan(p: Problem, planner: str, folder: Path, limit_s: float) -> PlanResult:
    """Solve ``p`` with ``planner`` within ``limit_s`` [s]; files under ``folder``."""
    search, heuristic = PLANNERS[planner]
    folder.mkdir(parents=True, exist_ok=True)
    domain = folder / "domain.pddl"
    domain.write_text(DOMAIN)
    task = folder / f"{p.name}-{planner}.pddl"
    task.write_text(problem_pddl(p))
    soln = task.with_name(task.name + ".soln")
    soln.unlink(missing_ok=True)
    cmd = [sys.executable, "-m", "pyperplan", "-s", search, "-H", heuristic, str(domain),
           str(task)]
    start = time.perf_counter()
    try:
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=limit_s)
    except subprocess.TimeoutExpired:
        return PlanResult(planner, "timeout", wall_s=time.perf_counter() - start)
    wall = time.perf_counter() - start
    log = done.stdout + done.stderr
    found = EXPANDED.findall(log)
    expanded = int(found[-1]) if found else 0
    if done.returncode != 0:
        last = log.strip().splitlines()[-1:] or [f"exit {done.returncode}"]
        return PlanResult(planner, "error", 0, expanded, wall, last[0][:200])
    if not soln.exists():
        return PlanResult(planner, "unsolved", 0, expanded, wall)
    steps = plan_steps(soln.read_text().splitlines())
    try:
        state = bw_strips.replay(p.start, steps)
    except bw_strips.Illegal as exc:
        return PlanResult(planner, "error", len(steps), expanded, wall, f"invalid plan: {exc}")
    missing = bw_strips.holds(state, p.goal())
    if missing:
        return PlanResult(planner, "error", len(steps), expanded, wall,
                          f"its plan leaves {missing} false")
    return PlanResult(planner, "solved", len(steps), expanded, wall)
