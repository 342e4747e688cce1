"""Benchmark: the cost of ordering a large conjunction (agents/lang/solving/ordering.py,
``agenda``), the threat check by index (``Threats``) against the pairwise one it replaced (kept
as the reference in tests/lang/solving/test_ordering_threats.py), in the same run on the same
situations: the initial state of each task, its goal as the conjunction. Both agendas must
agree; the figure is the ratio of their times, the needs of the plans computed before either
is timed (both share them), best of ``--repeat``.

    .venv/bin/python bench/ipc/agenda_cost.py                 # a visitall grid of 12 x 12
    .venv/bin/python bench/ipc/agenda_cost.py --grid 16 \\
        /tmp/ipc-downward/visitall-sat11-strips/domain.pddl \\
        /tmp/ipc-downward/visitall-sat11-strips/task03.pddl

Without task files it writes visitall (IPC 2011) grids: a robot at the centre of an N x N grid
that is to visit every cell, the conjunction of N * N ``(visited ...)`` literals whose plans
each need the robot somewhere that visiting any other cell moves it from."""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import click

ROOT = Path(__file__).resolve().parents[2]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from agents.lang import Engine, as_percepts, load_program_text  # noqa: E402
from agents.lang.core.store import PerceptIndex, store_of  # noqa: E402
from agents.lang.execution.effects import Effects  # noqa: E402
from agents.lang.solving.landmarks import needs  # noqa: E402
from agents.lang.solving.ordering import agenda  # noqa: E402
from agents.lang.solving.state import condition, pushable  # noqa: E402
from agents.lang.solving.task import Task  # noqa: E402
from agents.lang.solving.typed import TypedEffects  # noqa: E402
from tests.lang.solving.test_ordering_threats import pairwise_agenda  # noqa: E402
from world.pddl.files import load_task  # noqa: E402
from world.pddl.perception import perceive  # noqa: E402
from world.pddl.program import program_text  # noqa: E402

VISITALL = """(define (domain grid-visit-all)
 (:requirements :typing) (:types place - object)
 (:predicates (connected ?x ?y - place) (at-robot ?x - place) (visited ?x - place))
 (:action move :parameters (?curpos ?nextpos - place)
  :precondition (and (at-robot ?curpos) (connected ?curpos ?nextpos))
  :effect (and (at-robot ?nextpos) (not (at-robot ?curpos)) (visited ?nextpos))))
"""


def visitall_problem(n: int) -> str:
    """An N x N visitall problem, the robot at the centre."""
    cell = [f"c{x}-{y}" for x in range(n) for y in range(n)]
    links = [f"(connected c{x}-{y} c{x + dx}-{y + dy})" for x in range(n) for y in range(n)
             for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1))
             if 0 <= x + dx < n and 0 <= y + dy < n]
    start = f"c{n // 2}-{n // 2}"
    return (f"(define (problem grid-{n}) (:domain grid-visit-all)\n (:objects "
            + " ".join(cell) + " - place)\n (:init (at-robot " + start + f") (visited {start}) "
            + " ".join(links) + ")\n (:goal (and " + " ".join(f"(visited {c})" for c in cell)
            + ")))\n")


def situation(domain: Path, problem: Path):
    """(program, raw percepts, the goal's conjuncts) of the task's initial state."""
    task = load_task(domain, problem)
    program = load_program_text(program_text(task.domain, task, goals=False))
    types = task.object_types()
    raw = perceive({"objects": [[o, list(types[o])] for o, _ in task.objects],
                    "atoms": [list(a) for a in sorted(task.init)]}, "bench")
    return program, raw, tuple(g.text() for g in task.goal if not g.negated)


def fresh(program, raw) -> Task:
    index = PerceptIndex(as_percepts(raw))
    store = store_of(Engine(program).infer(index))
    effects = TypedEffects(program, Effects(program))
    effects.see(index, store)
    return Task(program, index, store, effects=effects)


def timed(order, program, raw, conds, repeat: int) -> tuple[float, list[str], int]:
    """Best time of ``order`` over ``repeat`` fresh tasks (needs computed first), its
    agenda and the unsatisfied conjuncts."""
    best, out, n = float("inf"), [], 0
    for _ in range(repeat):
        task = fresh(program, raw)
        unsat = [c for c in conds if pushable(condition(c)) and not task.holds(c)]
        for h in unsat:
            needs(task, h)
        t0 = time.perf_counter()
        out = order(task, conds)
        best, n = min(best, time.perf_counter() - t0), len(unsat)
    return best, out, n


@click.command()
@click.argument("files", nargs=-1, type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("--grid", default=12, show_default=True, help="Side of the visitall grid "
              "written when no FILES are given.")
@click.option("--repeat", default=3, show_default=True, help="Timings per agenda (best).")
def main(files: tuple[Path, ...], grid: int, repeat: int) -> None:
    """Time the agenda by index against the pairwise one on FILES (DOMAIN PROBLEM pairs)."""
    if len(files) % 2:
        raise click.UsageError("FILES are DOMAIN PROBLEM pairs: an odd number was given")
    pairs = list(zip(files[::2], files[1::2], strict=True))
    if not pairs:
        folder = Path(tempfile.mkdtemp(prefix="teleo-agenda-"))
        (folder / "domain.pddl").write_text(VISITALL)
        (folder / "grid.pddl").write_text(visitall_problem(grid))
        pairs = [(folder / "domain.pddl", folder / "grid.pddl")]
    print(f"{'task':40} {'conjuncts':>9} {'pairwise':>10} {'indexed':>10} {'ratio':>7}  same")
    for domain, problem in pairs:
        program, raw, conds = situation(domain, problem)
        old_s, old, n = timed(pairwise_agenda, program, raw, conds, repeat)
        new_s, new, _ = timed(lambda t, c: agenda(t, c), program, raw, conds, repeat)
        name = f"{problem.parent.name}/{problem.name}"[-40:]
        print(f"{name:40} {n:9d} {old_s:9.3f}s {new_s:9.3f}s {old_s / new_s:6.1f}x  "
              f"{'yes' if old == new else 'NO'}")
        if old != new:
            raise SystemExit(f"{name}: the agendas differ: {old[:5]} ... vs {new[:5]} ...")


if __name__ == "__main__":
    main()
