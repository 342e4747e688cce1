"""teleo on a Blocks World problem of bench/planning/bw_problems.py: the problem written as a
program and a scenario for the pymunk Blocks World (world/blocks), run by `teleo simulate`'s own
loop (tools.commands.simulate.simulate, in this process), and the run's figures: its actions, when
the goal first held, the problem solver's effort, the goal statuses its summary reports.

Goal forms (``mode``, a form and an order: "conjunction-listed", ...):
  conjunction  one user goal for the whole goal: ``(and (on ..) ...)`` once teleo reads it
               (CONJUNCTION_SYNTAX), until then a concept of the program whose :relations are
               the goal's `on` literals, ``(goal-state)``;
  list         one user goal per literal, a priority list, priorities 1, 2, ...;
and the literals in the order IPC lists them (``listed``: each tower top-down) or each tower
from its base (``bottom-up``).
The program is programs/blocks.tlp (its primitive skills; any goals section left out).
"""

from __future__ import annotations

import json
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

from bench.planning.bw_problems import Problem

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = ROOT / "programs" / "blocks.tlp"
FORMS = ("conjunction", "list")
ORDERS = ("listed", "bottom-up")
MODES = tuple(f"{f}-{o}" for f in FORMS for o in ORDERS)
GOAL_CONCEPT = "goal-state"
CONJUNCTION_SYNTAX = True
"""True once a goal may be written (and L1 L2 ...) (issue 22); then the conjunction is posted
as written instead of through the program's goal-state concept."""


def cycle_limit(n: int) -> int:
    """The cycles a problem of n blocks may take (issue 22's target: 10 n + 20)."""
    return 10 * n + 20


def conjunction_goal(p: Problem, order: str = "listed") -> tuple[str, str]:
    """(concepts to add to the program, the goal to post) for the whole goal as one goal."""
    literals = " ".join(f"(on {a} {b})" for a, b in p.goal(order))
    if CONJUNCTION_SYNTAX:
        return "", f"(and {literals})"
    return (f"  ((goal-state)\n   :relations ({literals}))\n", f"({GOAL_CONCEPT})")


def goals_of(p: Problem, mode: str) -> tuple[str, list[str]]:
    """(concepts to add, the user goals in priority order) of ``mode``."""
    if mode not in MODES:
        raise ValueError(f"goals_of: mode {mode!r}: expected one of {', '.join(MODES)}")
    form, order = mode.split("-", 1)
    if not p.goal(order):   # a goal state with every block on the table: nothing to post
        return "", []       # (the empty goal holds from the start, for pyperplan as for us)
    if form == "conjunction":
        extra, goal = conjunction_goal(p, order)
        return extra, [goal]
    return "", [f"(on {a} {b})" for a, b in p.goal(order)]


def program_text(extra_concepts: str = "") -> str:
    """programs/blocks.tlp without a goals section (it had the standing goal (clear A) until
    issue 22), with ``extra_concepts`` first among its concepts."""
    text = PROGRAM.read_text()
    start = re.search(r"^\(goals\b", text, re.M)
    if start is not None:
        text = text[:start.start()] + text[_close(text, start.start()):]
    return text.replace("(concepts\n", "(concepts\n" + extra_concepts, 1)


def _close(text: str, at: int) -> int:
    """The index after the parenthesis that closes the one at ``at`` (comments skipped)."""
    depth, k = 0, at
    while k < len(text):
        c = text[k]
        if c == ";":
            k = text.find("\n", k)
            k = len(text) if k < 0 else k
            continue
        depth += {"(": 1, ")": -1}.get(c, 0)
        k += 1
        if depth == 0:
            return k
    raise ValueError(f"{PROGRAM}: the section at offset {at} is not closed")


def scenario_text(p: Problem, program: Path, goals: list[str], cycles: int) -> str:
    """The scenario: the start state's towers on the table, the user goals posted at cycle 0
    with priorities 1, 2, ... in order."""
    towers = json.dumps([list(t) for t in p.start])
    posts = "".join(f'\n[[goals]]\nagent = "ME"\ngoal = "{g}"\npriority = {k + 1}\n'
                    for k, g in enumerate(goals))
    return (f'[run]\nname = "{p.name}"\nmode = "lockstep"\ncycles = {cycles}\nseed = 0\n'
            f'\n[world]\ndomain = "blocks"\ntowers = {towers}\n\n'
            f'[[agents]]\nid = "ME"\nprogram = "{program}"\n{posts}')


@dataclass
class TeleoRun:
    """What one run did: per cycle its actions, and how many of them the world refused
    (the run's trace counts them); the goal records of its summary; per cycle whether
    problem solving ran, and its chaining decisions and backtracks; the skills it ended
    with; wall time [s]; world counters at the end; the final snapshot."""

    actions: list[list[list]] = field(default_factory=list)
    refused: list[int] = field(default_factory=list)
    summary_goals: list[dict] = field(default_factory=list)
    solving: list[bool] = field(default_factory=list)
    pushes: int = 0
    backtracks: int = 0
    learned: tuple[str, ...] = ()
    wall_s: float = 0.0
    counters: dict = field(default_factory=dict)
    final: dict = field(default_factory=dict)
    error: str = ""


def allow_live_goals(count: int) -> None:
    """Let the goal-entry store hold ``count`` live user goals per agent (its limit,
    agents/processes/goal_store.MAX_LIVE_GOALS, is 16; a priority list of 30 blocks has up
    to 29 literals). Only this bench's processes are affected."""
    from agents.processes import goal_store

    goal_store.MAX_LIVE_GOALS = max(goal_store.MAX_LIVE_GOALS, count)


def run_teleo(p: Problem, mode: str, folder: Path, learned: Path | None = None) -> TeleoRun:
    """Write the problem under ``folder`` and run it for cycle_limit(n) cycles, starting
    from the skills in ``learned`` if given."""
    from agents.lang import LangError
    from tools.commands.scenario_check import load_checked
    from tools.commands.simulate import simulate
    from tools.records import sim_summary
    from world.errors import WorldError

    extra, goals = goals_of(p, mode)
    allow_live_goals(len(goals))
    folder.mkdir(parents=True, exist_ok=True)
    program = folder / f"{p.name}-{mode}.tlp"
    program.write_text(program_text(extra))
    path = folder / f"{p.name}-{mode}.toml"
    cycles = cycle_limit(p.n)
    path.write_text(scenario_text(p, program, goals, cycles))
    out = TeleoRun()
    start = time.perf_counter()
    try:
        scenario, _ = load_checked(path)
        run = simulate(scenario, cycles, learned=learned)
    except (LangError, WorldError) as exc:
        out.error = str(exc)
        return out
    out.wall_s = time.perf_counter() - start
    for record in run.records:
        me = record["ME"]
        out.actions.append(me["actions"])
        section = me.get("solver") or {}
        out.solving.append(bool(section.get("solving")))
        events = section.get("events", [])
        out.pushes += sum(": pushed " in e for e in events)
        out.backtracks += sum(": backtracked" in e for e in events)
    out.refused = refusals(run.trace, run.final)
    out.summary_goals = sim_summary.build(run, scenario, 0, cycles)["goals"]
    out.learned = run.learned["ME"]
    out.counters = run.final.get("counters", {}).get("ME", {})
    out.final = run.final
    return out


def refusals(trace: list[str], final: dict) -> list[int]:
    """Per cycle, how many of the agent's actions the world refused: the growth of its
    actions_failed counter from that cycle's trace line to the next (the last to the final
    snapshot's)."""
    failed = [json.loads(line)["counters"].get("ME", {}).get("actions_failed", 0)
              for line in trace]
    failed.append(final.get("counters", {}).get("ME", {}).get("actions_failed", 0))
    return [b - a for a, b in zip(failed, failed[1:], strict=False)]


def carried(skills: tuple[str, ...]) -> tuple[tuple[str, ...], int]:
    """The learned skills worth carrying to another problem, and how many were left out:
    those whose head is this bench's per-problem goal-state concept (it means another goal
    in every problem)."""
    from agents.lang.registry import clause_heads

    keep = tuple(s for s in skills
                 if not any(h == f"({GOAL_CONCEPT})" for h in clause_heads(s)))
    return keep, len(skills) - len(keep)


def write_skills(skills: tuple[str, ...], path: Path) -> Path:
    """A learned file of ``skills`` as `teleo simulate --learned-out` writes it."""
    from agents.lang.registry import learned_text

    path.write_text(learned_text(skills, str(PROGRAM)))
    return path
