"""Solving an IPC Blocks World or Logistics task again with the skills learned on it needs no
problem solving (issue 35: "with the skills learned from a task, the same task is solved with
at least 90 % fewer problem-solving cycles"; seed 000 learns a skill from each achieved subgoal, so
every subgoal the fresh run reached by problem solving has a skill the second run executes).

Tasks 4, 5, 6 and 9 each kept 2 cycles: the executive cleared a block for one conjunct's plan
and was left holding what it lifted; the solver, at that impasse, went on with another conjunct
(the first in written order) whose plan it then dropped, so what it did there (put the block
down) taught nothing. Now the solver goes on with the conjunct whose plan the executive's last
path served, nearest (agents/lang/solving/ordering.py, search.py), and the executive goes on
with a part of a plan its own path was for while the plan needs it (solver.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from test_solve import replayed  # pyperplan's reading of the files, not the world's

from tools.commands.solve import solve

BLOCKS = Path(__file__).resolve().parents[2] / "bench" / "ipc" / "suites" / "blocks"


@pytest.mark.parametrize("number", [4, 5, 6, 9])
def test_an_ipc_blocks_task_solved_again_needs_no_problem_solving(tmp_path, number):
    files = (BLOCKS / "domain.pddl", BLOCKS / f"task{number:02d}.pddl")
    learned = tmp_path / "l.learned"
    fresh = solve(*files, learned_out=learned)
    again = solve(*files, learned=learned)
    assert fresh.status == again.status == "achieved", (fresh.reason, again.reason)
    assert fresh.solving_cycles > 0 and again.solving_cycles == 0, (fresh, again)
    assert replayed(files, again.actions)
    assert len(again.actions) <= len(fresh.actions), (fresh.actions, again.actions)


LOGISTICS = BLOCKS.parent / "logistics"


def test_logistics_task03_solved_again_needs_no_problem_solving(tmp_path):
    """Task03 kept 6 of 26 cycles (77 %): the fresh run first chained (at obj21 apt1) off
    unloading it from tru1 (the first skill in program order), drove tru1 to apt1 and
    backtracked (tru1 could only be loaded where obj21 is to go); the skills learned fitted
    that detour's state. The primitive skills' ways are now ordered by the relaxed estimate
    (agents/lang/solving/ways.py), so the airplane is chosen first and no detour is made."""
    files = (LOGISTICS / "domain.pddl", LOGISTICS / "task03.pddl")
    learned = tmp_path / "l.learned"
    fresh = solve(*files, learned_out=learned)
    again = solve(*files, learned=learned)
    assert fresh.status == again.status == "achieved", (fresh.reason, again.reason)
    assert ["drive-truck", "tru1", "pos1", "apt1", "cit1"] != fresh.actions[0]
    assert fresh.solving_cycles > 0 and again.solving_cycles == 0, (fresh, again)
    assert replayed(files, fresh.actions) and replayed(files, again.actions)


def test_logistics_task04_plan_within_one_and_a_half_times_the_optimum():
    """Issue 35: plans at most 1.5x the best found; task04's optimum is 27 (A* with LM-cut,
    bench/ipc/ipc.py), and the run was 42 (x1.56)."""
    files = (LOGISTICS / "domain.pddl", LOGISTICS / "task04.pddl")
    out = solve(*files)
    assert out.status == "achieved" and replayed(files, out.actions)
    assert len(out.actions) <= 1.5 * 27, out.actions


RANDOM = ("(define (problem r) (:domain blocks) (:objects b0 b1 b2 b3 b4 - block) (:init "
          "(handempty) (ontable b0) (clear b4) (on b2 b0) (on b3 b2) (on b1 b3) (on b4 b1)) "
          "(:goal (and (on b1 b0) (on b3 b2) (on b4 b3))))")


def test_a_conjunct_in_passing_leaves_what_the_executives_own_path_cleared(tmp_path):
    """A random problem hypothesis found (tests/tools/test_solve_learned_starts.py): with its
    own skills the executive cleared b2 on its way to clearing b0 (a learned skill, no goal
    stack), then put b3, in its hand, straight back on b2 ((on b3 b2), a conjunct one action
    achieves, in passing), and went round in a circle until the goal failed. A conjunct in
    passing may not undo what the plan of the conjunct the path is for needs and holds, as
    with a goal stack it may not undo what the way under way achieved (solver.py)."""
    problem = tmp_path / "p.pddl"
    problem.write_text(RANDOM)
    domain = Path(__file__).resolve().parents[1] / "world" / "pddl" / "files" / \
        "blocks-domain.pddl"
    learned = tmp_path / "l.learned"
    fresh = solve(domain, problem, learned_out=learned)
    again = solve(domain, problem, learned=learned)
    assert fresh.status == again.status == "achieved", (fresh.reason, again.reason)
    assert again.solving_cycles == 0 and replayed((domain, problem), again.actions)
    assert len(again.actions) <= len(fresh.actions)
