"""Bad PDDL input (world/pddl/files.py, convert.py): one line naming the file, line and column
and what is wrong, never a traceback: syntax errors with what was expected, requirements and
constructs outside STRIPS named, undeclared objects, types and predicates named; the same
at `teleo check` of a scenario and at `teleo solve`."""

from __future__ import annotations

import sys

import pytest
from click.testing import CliRunner
from pddl_helpers import TRUCKS, write_problem

from tools.cli import cli
from world.errors import ConfigError
from world.pddl.files import load_domain, load_task

DOMAIN = TRUCKS[0].read_text()


def _domain_error(tmp_path, text: str) -> str:
    path = write_problem(tmp_path, text, "d.pddl")
    with pytest.raises(ConfigError) as exc:
        load_domain(path)
    assert "\n" not in str(exc.value)
    return str(exc.value)


def _problem_error(tmp_path, text: str) -> str:
    path = write_problem(tmp_path, text)
    with pytest.raises(ConfigError) as exc:
        load_task(TRUCKS[0], path)
    assert "\n" not in str(exc.value)
    return str(exc.value)


def test_a_syntax_error_names_file_line_column_and_what_was_expected(tmp_path):
    text = "(define (domain d)\n  (:requirements :strips)\n  (:predicates (p ?x)\n" \
           "  (:action a :parameters (?x)\n    :precondition (p ?x)\n    :effect (p ?x)))\n"
    msg = _domain_error(tmp_path, text)
    assert msg.startswith(f"{tmp_path / 'd.pddl'}:4:4: pddl: syntax error: expected a name, "
                          f"got ':action'")


def test_a_file_that_ends_early_says_so(tmp_path):
    msg = _domain_error(tmp_path, "(define (domain d)\n  (:requirements :strips)\n")
    assert msg.endswith("d.pddl:2:25: pddl: syntax error: expected one of '(', ')', got the "
                        "end of the file")


@pytest.mark.parametrize("requirement", [":conditional-effects", ":durative-actions",
                                         ":numeric-fluents", ":derived-predicates",
                                         ":timed-initial-literals"])
def test_an_unsupported_requirement_is_refused_by_name(tmp_path, requirement):
    text = DOMAIN.replace(":equality)", f":equality {requirement})")
    msg = _domain_error(tmp_path, text)
    assert f"pddl: requirement {requirement} is not supported" in msg
    assert msg.startswith(f"{tmp_path / 'd.pddl'}:4:")


@pytest.mark.parametrize("requirement", [":adl", ":disjunctive-preconditions",
                                         ":quantified-preconditions"])
def test_a_syntax_requirement_declared_and_not_used_runs(tmp_path, requirement):
    text = DOMAIN.replace(":equality)", f":equality {requirement})")
    path = write_problem(tmp_path, text, "d.pddl")
    assert load_domain(path).name == "trucks"


@pytest.mark.parametrize("declared", ["", " :adl"])
def test_a_conditional_effect_is_refused_naming_it_and_its_requirement(tmp_path, declared):
    text = DOMAIN.replace(":equality)", f":equality{declared})").replace(
        "(ready)))\n", "(when (ready) (ready))))\n", 1)
    assert "(when" in text
    msg = _domain_error(tmp_path, text)
    assert "conditional effects (when; :conditional-effects) not supported" in msg
    assert msg.startswith(f"{tmp_path / 'd.pddl'}:")


def test_a_disjunction_declared_by_adl_is_refused_at_its_place(tmp_path):
    text = DOMAIN.replace(":equality)", ":equality :adl)").replace(
        "(not (broken ?v)))", "(or (not (broken ?v)) (ready)))", 1)
    assert "(or" in text
    msg = _domain_error(tmp_path, text)
    assert "disjunctions (or; :disjunctive-preconditions) not supported" in msg
    assert msg.startswith(f"{tmp_path / 'd.pddl'}:15:")


def test_an_undeclared_type_in_the_domain_is_named(tmp_path):
    text = DOMAIN.replace("?x - parcel ?v - vehicle ?p - place)\n    :precondition (and (in",
                          "?x - parsel ?v - vehicle ?p - place)\n    :precondition (and (in")
    msg = _domain_error(tmp_path, text)
    assert "d.pddl:24:23:" in msg and "?x is of the undeclared type 'parsel'" in msg


def test_an_undeclared_predicate_in_an_action_is_named(tmp_path):
    text = DOMAIN.replace("(not (broken ?v)))", "(not (brokn ?v)))")
    assert "d.pddl:15:12: pddl: action drive: undeclared predicate 'brokn' in (not (brokn ?v))" in \
        _domain_error(tmp_path, text)


PROBLEM = """(define (problem q) (:domain trucks)
  (:objects t1 - truck home shop - place p1 - parcel)
  (:init (at t1 home) (parcel-at p1 home))
  (:goal (and (parcel-at p1 shop))))
"""


@pytest.mark.parametrize("old, new, words, where", [
    ("(at t1 home)", "(at t2 home)", "the initial state: undeclared object 't2' in (at t2 home)",
     ":3:14"),
    ("(parcel-at p1 shop)", "(parcel-at p1 mars)",
     "the goal: undeclared object 'mars' in (parcel-at p1 mars)", ":4:"),
    ("(at t1 home)", "(on t1 home)", "undeclared predicate 'on' in (on t1 home)", ":3:"),
    ("p1 - parcel", "p1 - box", "object p1 is of the undeclared type 'box'", ":2:"),
    ("(parcel-at p1 home)", "(parcel-at p1)", "parcel-at takes 2 argument(s), got 1", ":3:"),
    ("(:domain trucks)", "(:domain lorries)", "the problem is for domain 'lorries', not "
     "'trucks'", ":1:"),
])
def test_a_problem_naming_something_undeclared_is_refused_naming_it(tmp_path, old, new, words,
                                                                     where):
    msg = _problem_error(tmp_path, PROBLEM.replace(old, new))
    assert words in msg
    assert msg.startswith(f"{tmp_path / 'p.pddl'}{where}")


def test_a_missing_file_is_one_line(tmp_path):
    with pytest.raises(ConfigError, match="cannot read the file"):
        load_task(TRUCKS[0], tmp_path / "none.pddl")


def test_without_the_pddl_package_the_world_says_how_to_install_it(monkeypatch):
    import world.pddl.files as files

    monkeypatch.setattr(files, "_PARSERS", [])
    monkeypatch.setitem(sys.modules, "pddl.parser.domain", None)
    with pytest.raises(ConfigError, match=r"pip install 'teleo\[pddl\]'"):
        load_domain(TRUCKS[0])


def _scenario(tmp_path, problem: str) -> str:
    write_problem(tmp_path, problem)
    (tmp_path / "d.pddl").write_text(DOMAIN)
    (tmp_path / "prog.tlp").write_text("(concepts ((ready) :percepts ((ready true))))\n")
    path = tmp_path / "s.toml"
    path.write_text('[run]\nname = "bad"\ncycles = 3\n\n[world]\ndomain = "pddl"\n'
                    'domain_file = "d.pddl"\nproblem_file = "p.pddl"\n\n[[agents]]\n'
                    'id = "ME"\nprogram = "prog.tlp"\n')
    return str(path)


def test_teleo_check_of_a_scenario_names_the_pddl_file_line_and_column(tmp_path):
    path = _scenario(tmp_path, PROBLEM.replace("(at t1 home)", "(at t2 home)"))
    out = CliRunner().invoke(cli, ["check", path])
    assert out.exit_code == 1 and "Traceback" not in out.output
    assert f"{tmp_path / 'p.pddl'}:3:14: pddl: the initial state: undeclared object 't2'" \
        in out.output


def test_a_good_scenario_checks_and_simulates(tmp_path):
    path = _scenario(tmp_path, PROBLEM)
    out = CliRunner().invoke(cli, ["check", path])
    assert out.exit_code == 0, out.output
    out = CliRunner().invoke(cli, ["simulate", path, "--no-record"])
    assert "3 cycles" in out.output and "Traceback" not in out.output


def test_teleo_solve_of_a_bad_problem_is_one_line(tmp_path):
    bad = write_problem(tmp_path, PROBLEM.replace("(:init", "(:init (at"))
    out = CliRunner().invoke(cli, ["solve", str(TRUCKS[0]), str(bad)])
    assert out.exit_code == 1 and "Traceback" not in out.output
    assert out.output.count("\n") == 1 and f"{bad}:3:" in out.output


def test_a_syntax_error_leaves_the_next_file_readable(tmp_path):
    bad = DOMAIN.replace(":effect", ":efect", 1)
    assert "syntax error" in _domain_error(tmp_path, bad)
    assert load_domain(write_problem(tmp_path, DOMAIN, "good.pddl")).name == "trucks"
