"""`teleo solve DOMAIN PROBLEM` (tools/commands/solve.py) on small IPC tasks: the goal achieved,
exit 0, and the executed plan replayed independently by pyperplan's parser and grounding (a
dev dependency) to a state that satisfies the goal; the skills it learned carried to the next
run; a run cut short is `limit`, exit 1."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner
from pyperplan.grounding import ground
from pyperplan.pddl.parser import Parser

from tools.cli import cli

FILES = Path(__file__).resolve().parents[1] / "world" / "pddl" / "files"  # vendored tasks
BLOCKS = (FILES / "blocks-domain.pddl", FILES / "blocks-task01.pddl")
BLOCKS2 = (FILES / "blocks-domain.pddl", FILES / "blocks-task02.pddl")
GRIPPER = (FILES / "gripper-domain.pddl", FILES / "gripper-task01.pddl")
TRUCKS = (FILES / "trucks-domain.pddl", FILES / "trucks-problem.pddl")


def _solve(files, *extra: str) -> tuple[int, dict]:
    result = CliRunner().invoke(cli, ["solve", str(files[0]), str(files[1]), "--json", *extra])
    return result.exit_code, json.loads(result.output)


def replayed(files, actions: list[list[str]]) -> bool:
    """Whether ``actions`` are applicable in turn from the problem's start and end in a state
    satisfying its goal, by pyperplan's reading of the files."""
    parser = Parser(str(files[0]), str(files[1]))
    task = ground(parser.parse_problem(parser.parse_domain()))
    ops = {op.name: op for op in task.operators}
    state = task.initial_state
    for a in actions:
        op = ops.get(f"({' '.join(a)})")
        assert op is not None and op.applicable(state), a
        state = op.apply(state)
    return task.goal_reached(state)


@pytest.mark.parametrize("files", [BLOCKS, BLOCKS2, GRIPPER], ids=lambda f: f[1].stem)
def test_solve_achieves_the_goal_and_the_plan_replays(files):
    code, out = _solve(files)
    assert (code, out["status"]) == (0, "achieved"), out
    assert out["actions"] and all(a == [x.lower() for x in a] for a in out["actions"])
    assert replayed(files, out["actions"])
    assert out["cycles"] >= len(out["actions"]) and out["solving_cycles"] >= 1
    assert out["learned"] >= 1 and out["plan_length"] == len(out["actions"])


def test_the_typed_domain_with_either_and_negations_is_solved():
    code, out = _solve(TRUCKS)
    assert (code, out["status"]) == (0, "achieved")
    assert out["actions"][0] == ["load", "p1", "t1", "home"]


def test_negated_goals_and_preconditions_are_pursued(tmp_path):
    problem = tmp_path / "van.pddl"
    problem.write_text(TRUCKS[1].read_text().replace(
        "(:goal (and (parcel-at p1 shop) (parcel-at p2 home)))",
        "(:goal (and (at v1 shop) (not (parcel-at p1 home))))"))
    code, out = _solve((TRUCKS[0], problem))
    assert (code, out["status"], out["goal"]) == \
        (0, "achieved", "(and (at v1 shop) (not-parcel-at p1 home))"), out
    assert ["service", "v1"] in out["actions"]   # v1 is broken: it must be serviced to drive


def test_learned_skills_make_the_same_problem_need_less_problem_solving(tmp_path):
    learned = tmp_path / "learned.tlp"
    code, first = _solve(BLOCKS, "--learned-out", str(learned))
    assert code == 0 and learned.exists() and first["learned_file"] == str(learned)
    checked = CliRunner().invoke(cli, ["check", str(learned)])   # names its program, kept
    assert checked.exit_code == 0 and "learned-program.tlp" in checked.output
    code, again = _solve(BLOCKS, "--learned", str(learned))
    assert (code, again["status"]) == (0, "achieved")
    assert again["solving_cycles"] < first["solving_cycles"]
    assert replayed(BLOCKS, again["actions"])


def test_a_run_cut_short_is_limit_and_exit_1():
    code, out = _solve(BLOCKS, "--cycles", "2")
    assert (code, out["status"], out["cycles"]) == (1, "limit", 2)
    assert "2 cycles ran out" in out["reason"]


def test_the_text_output_names_the_status_and_the_plan():
    result = CliRunner().invoke(cli, ["solve", str(BLOCKS[0]), str(BLOCKS[1])])
    assert result.exit_code == 0
    first, goal, *plan = result.output.splitlines()
    assert first.startswith("blocks blocks-4-0: achieved in ")
    assert goal == "  goal (and (on d c) (on c b) (on b a))"
    assert plan[0].split(None, 1)[1].startswith("(pick-up") or "unstack" in plan[0]


def test_a_run_out_of_time_is_limit_with_its_reason_and_exit_1():
    # 1 ms: spent before the first cycle whatever the machine (parsing alone takes longer)
    code, out = _solve(BLOCKS2, "--time-limit", "0.001")
    assert (code, out["status"], out["actions"], out["learned_file"]) == (1, "limit", [], None)
    assert out["reason"].startswith("the time limit of 0.001 s ran out")


def test_the_time_limits_watch_keeps_the_plan_the_run_executed():
    from tools.commands.solve import _solve as run_solve
    from tools.commands.solve import _Watch, solve

    # a run cut short mid-parse first: the next one in the process parses afresh
    assert solve(BLOCKS2[0], BLOCKS2[1], time_limit=0.001).status == "limit"
    watch = _Watch()
    result = run_solve(BLOCKS2[0], BLOCKS2[1], None, None, "", None, watch)
    assert result.status == "achieved" and len(result.actions) > 4
    assert watch.actions == result.actions and watch.cycles == result.cycles


def test_a_bad_time_limit_is_a_usage_error():
    result = CliRunner().invoke(cli, ["solve", str(BLOCKS[0]), str(BLOCKS[1]),
                                      "--time-limit", "0"])
    assert result.exit_code == 2 and "--time-limit" in result.output


def test_a_goal_of_many_literals_longer_than_a_posted_goal_used_to_be_is_solved(tmp_path):
    """A PDDL problem's goal may be thousands of characters (every cell of a grid to visit);
    a line of 24 cells with long names gives one over 5,000."""
    cells = [f"cell-{k:02d}-" + "x" * 200 for k in range(24)]
    domain = """(define (domain line) (:requirements :strips :typing) (:types cell)
  (:predicates (at ?c - cell) (next ?a - cell ?b - cell) (visited ?c - cell))
  (:action move :parameters (?a - cell ?b - cell) :precondition (and (at ?a) (next ?a ?b))
    :effect (and (not (at ?a)) (at ?b) (visited ?b))))"""
    links = " ".join(f"(next {a} {b}) (next {b} {a})"
                     for a, b in zip(cells, cells[1:], strict=False))
    goal = " ".join(f"(visited {c})" for c in cells)
    problem = (f"(define (problem walk) (:domain line) (:objects {' '.join(cells)} - cell)\n"
               f"  (:init (at {cells[0]}) (visited {cells[0]}) {links})\n"
               f"  (:goal (and {goal})))")
    assert len(goal) > 5000
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    files = (tmp_path / "d.pddl", tmp_path / "p.pddl")
    code, out = _solve(files)
    assert (code, out["status"]) == (0, "achieved"), out
    assert replayed(files, out["actions"]) and len(out["actions"]) == len(cells) - 1


def test_a_goal_reached_by_many_ways_through_the_same_literals_is_solved(tmp_path):
    """Each (p_i) and (q_i) needs both (p_i-1) and (q_i-1): regressing (p22) along every way
    walks 2**22 chains through the same 44 literals; the conjuncts' needs are read from a
    bounded regression, so the first cycle ends and the plan is the shortest, 44 actions."""
    n = 22
    preds = " ".join(f"(p{i}) (q{i})" for i in range(n + 1))
    acts = "\n".join(f"(:action make-{x}{i} :parameters () :precondition (and (p{i - 1}) "
                     f"(q{i - 1})) :effect ({x}{i}))" for i in range(1, n + 1) for x in "pq")
    (tmp_path / "d.pddl").write_text(f"(define (domain lattice) (:requirements :strips) "
                                     f"(:predicates {preds})\n{acts})")
    (tmp_path / "p.pddl").write_text(f"(define (problem l) (:domain lattice) (:init (p0) (q0))"
                                     f" (:goal (and (p{n}) (q{n}))))")
    files = (tmp_path / "d.pddl", tmp_path / "p.pddl")
    code, out = _solve(files, "--time-limit", "60")
    assert (code, out["status"]) == (0, "achieved"), out["reason"]
    assert len(out["actions"]) == 2 * n and replayed(files, out["actions"])
