"""The units of work of bench/planning/planning.py, each a top-level function a process pool can
run: a pyperplan search, a teleo run in one goal form, the learning curve (problems in order, the
skills each learned carried to the next) and a held-out problem with or without skills. A
problem travels as (n, seed) and is drawn again in the worker (bench/planning/bw_problems.py is
deterministic)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from bench.planning.bw_check import Verdict, check
from bench.planning.bw_problems import problem
from bench.planning.bw_pyperplan import PlanResult, run_pyperplan
from bench.planning.bw_teleo import carried, goals_of, run_teleo, write_skills

Key = tuple[int, int]
"""A problem: (blocks, seed)."""


def plan(key: Key, planner: str, folder: str, limit_s: float) -> PlanResult:
    """pyperplan's ``planner`` on problem ``key``."""
    n, seed = key
    return run_pyperplan(problem(n, seed), planner, Path(folder) / f"pddl-{n}", limit_s)


def teleo(key: Key, mode: str, folder: str, learned: str = "") -> Verdict:
    """teleo on problem ``key`` with the goal given as ``mode``, checked; from the skills in
    the file ``learned`` if given."""
    p = problem(*key)
    run = run_teleo(p, mode, Path(folder) / f"teleo-{p.n}", Path(learned) if learned else None)
    return check(p, run, len(goals_of(p, mode)[1]))


@dataclass(frozen=True)
class CurveStep:
    """One problem of the learning curve: its verdict, the skills it ended with (carried on),
    and those left out of the carry (bw_teleo.carried)."""

    key: Key
    verdict: Verdict
    skills: int
    dropped: int


def curve(keys: list[Key], mode: str, folder: str) -> tuple[list[CurveStep], str]:
    """The problems ``keys`` in order, each from the skills the ones before it learned
    (``--learned`` / ``--learned-out`` of `teleo simulate`, in this process). Returns the
    steps and the learned file after the last."""
    base = Path(folder) / "curve"
    base.mkdir(parents=True, exist_ok=True)
    learned: Path | None = None
    steps, count = [], 0
    for k, key in enumerate(keys):
        p = problem(*key)
        run = run_teleo(p, mode, base, learned)
        verdict = check(p, run, len(goals_of(p, mode)[1]))
        dropped = 0
        if not run.error:       # a run that did not start passes on what it was given
            skills, dropped = carried(run.learned)
            learned, count = write_skills(skills, base / f"learned-{k + 1}.tlp"), len(skills)
        steps.append(CurveStep(key, verdict, count, dropped))
    return steps, str(learned) if learned else ""
