"""`teleo pddl program` (world/pddl/program.py, tools/commands/pddl.py): the program of a domain
loads and passes `teleo check`, prints back as itself, reads the world's percepts as the
atoms they are, states each operator's effects, and takes the user's own clauses beside it."""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from pddl_helpers import BLOCKS, GRIPPER, TRUCKS, world_of

from agents.lang import Engine, load_program_text
from agents.lang.reading.printer import program_text as printed
from tools.cli import cli
from world.domain import get_domain
from world.pddl.files import load_domain, load_task
from world.pddl.program import goal_text, program_text, static_predicates

DOMAINS = [BLOCKS, GRIPPER, TRUCKS]


@pytest.mark.parametrize("files", DOMAINS, ids=lambda f: f[0].stem)
def test_the_program_passes_teleo_check(files, tmp_path):
    out = tmp_path / "p.tlp"
    result = CliRunner().invoke(cli, ["pddl", "program", str(files[0]), "--problem",
                                      str(files[1]), "--out", str(out)])
    assert result.exit_code == 0, result.output
    checked = CliRunner().invoke(cli, ["check", str(out)])
    assert checked.exit_code == 0 and ": ok (" in checked.output, checked.output


@pytest.mark.parametrize("files", DOMAINS, ids=lambda f: f[0].stem)
def test_the_program_prints_back_as_itself(files):
    program = load_program_text(program_text(load_domain(files[0])))
    again = load_program_text(printed(program))
    assert printed(again) == printed(program)
    assert [(s.head, s.start, s.actions, s.effects) for s in again.skills] == \
        [(s.head, s.start, s.actions, s.effects) for s in program.skills]


def test_beliefs_are_the_true_atoms():
    world = world_of(TRUCKS)
    engine = Engine(load_program_text(program_text(world.task.domain)))
    percepts = get_domain("pddl").perceive(world.snapshot_dict(), "ME")
    beliefs = {str(b) for b in engine.infer(percepts)}
    atoms = {"(" + " ".join(a) + ")" for a in world.snapshot_dict()["atoms"]}
    assert atoms and {b for b in beliefs if not b.startswith("(not-")} == atoms
    assert {b for b in beliefs if b.startswith("(not-broken")} == {"(not-broken t1)"}


def test_one_skill_per_add_effect_each_with_the_operator_as_its_action():
    program = load_program_text(program_text(load_domain(BLOCKS[0])))
    stack = [s for s in program.skills if s.actions[0].name == "*stack"]
    assert sorted(str(s.head) for s in stack) == ["(clear ?x)", "(handempty)", "(on ?x ?y)"]
    on = next(s for s in stack if s.head.pred == "on")
    assert [str(c) for c in on.start] == ["(holding ?x)", "(clear ?y)"]
    assert [str(e) for e in on.effects] == ["(clear ?x)", "(handempty)",
                                            "(not (holding ?x))", "(not (clear ?y))"]


def test_equality_negation_either_and_constants_become_tests_and_conditions():
    text = program_text(load_domain(TRUCKS[0]))
    assert ":start ((at ?v ?from) (link ?from ?to) (<> ?from ?to) (not-broken ?v))" in text
    assert ":start ((at ?v ?p) (= ?p depot))" in text
    assert "(object ?v type truck)" in text and "(object ?v type van)" in text


def test_the_problem_goal_is_one_conjunction():
    task = load_task(*BLOCKS)
    assert goal_text(task) == "(and (on d c) (on c b) (on b a))"
    program = load_program_text(program_text(task.domain, task))
    assert [str(g.literal) for g in program.goals] == ["(and (on d c) (on c b) (on b a))"]


def test_a_users_own_concepts_and_skills_go_beside_the_generated_ones(tmp_path):
    extra = tmp_path / "mine.tlp"
    extra.write_text("(concepts\n  ((tower ?x ?y ?z)\n   :relations ((on ?x ?y) (on ?y ?z))))\n"
                     "(skills\n  ((tower ?x ?y ?z)\n   :percepts ((object ?x) (object ?y) "
                     "(object ?z))\n   :subgoals ((on ?y ?z) (on ?x ?y))))\n")
    out = tmp_path / "p.tlp"
    result = CliRunner().invoke(cli, ["pddl", "program", str(BLOCKS[0]), "--extra", str(extra),
                                      "--out", str(out)])
    assert result.exit_code == 0, result.output
    program = load_program_text(out.read_text())
    assert "tower" in program.concepts and program.skills[-1].head.pred == "tower"
    assert "on" in program.concepts


def test_a_bad_domain_is_one_line(tmp_path):
    bad = tmp_path / "d.pddl"
    bad.write_text("(define (domain d) (:requirements :strips :conditional-effects))")
    result = CliRunner().invoke(cli, ["pddl", "program", str(bad)])
    assert result.exit_code == 1 and result.output.count("\n") == 1
    assert "requirement :conditional-effects is not supported" in result.output


def test_a_required_negation_becomes_a_concept_the_deleting_operators_achieve():
    text = program_text(load_domain(TRUCKS[0]))
    program = load_program_text(text)
    [clause] = program.concepts["not-broken"]
    assert [str(r) for r in clause.relations] == ["(not (broken ?v))"]
    service = [s for s in program.skills if s.actions[0].name == "*service"]
    assert sorted(str(s.head) for s in service) == ["(not-broken ?v)", "(ready)"]
    assert ":start ((at ?v ?from) (link ?from ?to) (<> ?from ?to) (not-broken ?v))" in text


def test_the_program_is_the_same_in_every_process():
    """The pddl package keeps a conjunction as a set, whose order follows the process's hash
    seed; the program keeps the file's order whatever the seed."""
    import os
    import subprocess
    import sys

    code = ("import sys; from world.pddl.files import load_task; "
            "from world.pddl.program import program_text; "
            "print(program_text(load_task(sys.argv[1], sys.argv[2]).domain))")
    outs = {subprocess.run([sys.executable, "-c", code, str(BLOCKS[0]), str(BLOCKS[1])],
                           env={**os.environ, "PYTHONHASHSEED": seed}, capture_output=True,
                           text=True, check=True).stdout for seed in ("1", "2", "3")}
    assert len(outs) == 1
    assert ":start ((on ?x ?y) (clear ?x) (handempty))" in outs.pop()


def test_a_static_precondition_is_matched_among_the_percepts_first():
    # gripper is untyped: (room ?r), (ball ?b), (gripper ?g) no operator changes; matched
    # first, they narrow a parameter's objects before every object of the problem is tried
    # (the solver looks at a bounded number of percept matches: satellite's (satellite ?s)
    # was out of reach behind its other objects)
    model = load_domain(GRIPPER[0])
    assert static_predicates(model) == {"room", "ball", "gripper"}
    program = load_program_text(program_text(model))
    pick = next(s for s in program.skills if s.actions[0].name == "*pick"
                and s.head.pred == "carry")
    assert [str(p) for p in pick.percepts][:3] == [
        "(ball _ arg1 ?obj)", "(room _ arg1 ?room)", "(gripper _ arg1 ?gripper)"]
    assert "(ball ?obj)" in [str(c) for c in pick.start]   # still a start condition
    move = next(s for s in program.skills if s.actions[0].name == "*move")
    assert [str(p) for p in move.percepts][:2] == ["(room _ arg1 ?from)", "(room _ arg1 ?to)"]
    blocks = program_text(load_domain(BLOCKS[0]))   # nothing static: as before
    assert static_predicates(load_domain(BLOCKS[0])) == frozenset()
    assert ":percepts ((object ?x type block) (object ?y type block))" in blocks
