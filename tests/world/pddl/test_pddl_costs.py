"""Action costs (world/pddl/costs.py): a domain declaring `:action-costs` runs with its costs
ignored and says so (the world, `teleo pddl program`, `teleo solve`); any other number is
refused as numeric fluents at file:line:col; an operator that only adds to the cost (no add
effect) last in the file still makes a program that loads."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner
from pddl_helpers import FILES, write_problem

from agents.lang import load_program_text
from bench.ipc import strips
from tools.cli import cli
from world.errors import ConfigError
from world.pddl.costs import NOTE
from world.pddl.files import load_domain, load_task
from world.pddl.program import program_text

ROADS = (FILES / "roads-costs-domain.pddl", FILES / "roads-costs-problem.pddl")


def test_a_domain_with_action_costs_loads_with_a_note_and_its_plain_strips_part():
    task = load_task(*ROADS)
    assert task.domain.notes == (NOTE,) and "ignored" in NOTE
    drive = task.domain.operator("drive")
    assert [a.text() for a in drive.add] == ["(at ?t ?b)"]
    assert [d.text() for d in drive.delete] == ["(at ?t ?a)"]
    assert task.domain.operator("honk").add == () and task.domain.operator("honk").delete == ()
    assert ("road", "x", "y") in task.init and all(a[0] in ("at", "road") for a in task.init)


def test_the_program_says_costs_are_ignored_and_loads_with_a_skill_less_operator_last():
    text = program_text(load_domain(ROADS[0]))
    assert "; Note: action costs (:action-costs) are ignored" in text
    assert "(no skill: it achieves no concept)" in text.splitlines()[-2]
    program = load_program_text(text)   # the closing parenthesis not swallowed by the comment
    assert [str(s.head) for s in program.skills] == ["(at ?t ?b)"]


def test_teleo_solve_runs_it_states_the_note_and_the_plan_replays():
    result = CliRunner().invoke(cli, ["solve", str(ROADS[0]), str(ROADS[1]), "--json"])
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["status"] == "achieved" and data["notes"] == [NOTE]
    assert data["actions"] == [["drive", "t1", "x", "y"], ["drive", "t1", "y", "z"]]
    assert strips.check(strips.load(*ROADS), data["actions"]).valid   # its own cost stripping
    text = CliRunner().invoke(cli, ["solve", str(ROADS[0]), str(ROADS[1])])
    assert "  note: action costs (:action-costs) are ignored" in text.output


@pytest.mark.parametrize("old,new,what", [
    ("(road ?a ?b))\n", "(road ?a ?b) (> (road-length ?a ?b) 3))\n", "(>)"),
    ("(increase (total-cost) 1)", "(increase (road-length ?a ?a) 1)", "(increase)"),
])
def test_any_other_number_is_refused_as_numeric_fluents_at_its_place(tmp_path, old, new, what):
    text = ROADS[0].read_text()
    assert old in text
    path = write_problem(tmp_path, text.replace(old, new), "d.pddl")
    with pytest.raises(ConfigError) as exc:
        load_domain(path)
    msg = str(exc.value)
    assert "\n" not in msg and f"pddl: numeric fluents {what} not supported" in msg
    line = next(k for k, s in enumerate(text.replace(old, new).splitlines(), 1)
                if new.split("\n")[0].strip() in s)
    assert msg.startswith(f"{path}:{line}:")


def test_without_the_requirement_functions_are_still_refused(tmp_path):
    text = ROADS[0].read_text().replace(" :action-costs", "")
    path = write_problem(tmp_path, text, "d.pddl")
    with pytest.raises(ConfigError, match=r"d\.pddl:8:\d+: pddl: numeric fluents \(:functions\)"):
        load_domain(path)


def test_a_syntax_error_after_a_blanked_cost_keeps_its_line_and_column(tmp_path):
    text = ROADS[1].read_text().replace("(:goal (and (at t1 z)))", "(:goal (and (at t1 z))")
    path = write_problem(tmp_path, text)
    with pytest.raises(ConfigError) as exc:
        load_task(ROADS[0], path)
    assert str(exc.value).startswith(f"{path}:9:") and "syntax error" in str(exc.value)


def test_costs_used_without_declaring_the_requirement_run_too(tmp_path):
    # (:functions (total-cost)) alone, no :action-costs: as some IPC files are written
    text = ROADS[0].read_text().replace(" :action-costs", "").replace(
        "\n              (road-length ?a ?b - place) - number", "").replace(
        "(increase (total-cost) (road-length ?a ?b))", "(increase (total-cost) 1)")
    assert "road-length" not in text
    path = write_problem(tmp_path, text, "d.pddl")
    task = load_task(path, ROADS[1])
    assert task.domain.notes == (NOTE,) and task.domain.operator("drive").add
