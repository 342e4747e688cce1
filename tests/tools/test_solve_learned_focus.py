"""Solving an IPC Blocks World task again with the skills learned on it needs no problem
solving (issue 35: "with the skills learned from a task, the same task is solved with at least
90 % fewer problem-solving cycles"; seed 000 learns a skill from each achieved subgoal, so
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
