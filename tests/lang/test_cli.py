"""`teleo check`, `teleo infer` and `teleo step` on real files."""

from __future__ import annotations

import json

from click.testing import CliRunner

from tools.cli import cli

from .conftest import FIX, PROGRAMS, ROOT

T3 = str(FIX / "table3_percepts.txt")
CONCEPTS = ["-I", str(FIX / "table2_concepts.tlp"), "-I", str(FIX / "driving_support.tlp")]


def invoke(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_check_accepts_valid_programs():
    result = invoke("check", ROOT / "programs" / "blocks.tlp", PROGRAMS / "minidrive.tlp")
    assert result.exit_code == 0
    assert "blocks.tlp: ok (11 concepts, 7 skills, 0 goals)" in result.output


def test_check_reports_all_errors_and_exits_1(tmp_path):
    bad = tmp_path / "bad.tlp"
    bad.write_text("(concepts ((a ?x) :percepts ((o ?x)) :relations ((b ?x) (c ?x ?y))))")
    result = invoke("check", bad)
    assert result.exit_code == 1
    assert f"{bad}:1:50: undefined concept 'b'" in result.output
    assert f"{bad}:1:57: undefined concept 'c'" in result.output
    assert "bad.tlp: 2 errors" in result.output


def test_check_table6_with_its_concepts_warns_about_typos():
    result = invoke("check", FIX / "table6_skills.tlp", *CONCEPTS)
    assert result.exit_code == 0
    assert "warning: ':require' read as ':requires'" in result.output


def test_infer_prints_sorted_beliefs():
    result = invoke("infer", FIX / "table2_concepts.tlp", "--percepts", T3, *CONCEPTS[2:])
    assert result.exit_code == 0, result.output
    assert result.output.splitlines() == [
        "(address-in-front ME 2 B)", "(at-desired-speed ME)", "(at-street ME B)",
        "(in-segment ME S2724)", "(not-hitting-pedestrians ME)", "(segment-at-street S2724 B)"]


def test_step_saves_state_and_continues_from_it(tmp_path):
    percepts = tmp_path / "p.json"
    percepts.write_text(json.dumps([["self", "ME", "speed", 15.0, "limit", 25, "heading", 0.0,
                                     "position", 0],
                                    ["package", "PACKET1", "address", 4, "delivered", "NIL"]]))
    state = tmp_path / "state.json"
    first = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", percepts,
                   "--goal", "(package-delivered PACKET1):5", "--save-state", state)
    assert first.exit_code == 0, first.output
    assert "actions: (*forward 2)" in first.output
    assert "5 g4       active    (package-delivered PACKET1)" in first.output
    second = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", percepts,
                    "--state", state, "--json")
    data = json.loads(second.output)
    assert data["decision"]["actions"] == [["*forward", 2]]
    assert [s["mode"] for s in data["decision"]["path"]] == ["continued", "continued"]
    assert data["state"]["cycle"] == 2 and ["package", "PACKET1", "address", 4, "delivered",
                                            "NIL"] not in data["beliefs"]


def test_step_reports_bad_goal_and_bad_percepts(tmp_path):
    result = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", T3, "--goal", "(fly ME)")
    assert result.exit_code == 1 and "undefined concept 'fly'" in result.output
    bad = tmp_path / "bad.txt"
    bad.write_text("(self ME speed)")
    result = invoke("infer", PROGRAMS / "minidrive.tlp", "--percepts", bad)
    assert result.exit_code == 1 and "bad.txt:1:1: percept (self ME speed)" in result.output


def test_a_file_that_cannot_be_read_is_named_once_without_a_line(tmp_path):
    missing = tmp_path / "nosuch.tlp"
    checked = invoke("check", missing)
    assert checked.exit_code == 1
    assert f"{missing}: cannot read file: No such file or directory" in checked.output
    scenario = tmp_path / "nosuch.toml"
    told = invoke("check", scenario)
    assert told.exit_code == 1 and told.output.strip() == f"{scenario}: scenario file not found"
    state = tmp_path / "nosuch.json"
    stepped = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", T3, "--state", state)
    assert stepped.exit_code == 1
    assert stepped.output.strip() == f"{state}: cannot read file: No such file or directory"


def test_step_holds_a_goals_priority_to_the_rules_of_goal_post():
    goal = "(package-delivered PACKET1)"
    zero = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", T3, "--goal", f"{goal}:0")
    assert zero.exit_code == 2 and "priority 0 is not in 1..1000000" in zero.output
    negative = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", T3, "--goal", f"{goal}:-4")
    assert negative.exit_code == 2 and "priority -4 is not in 1..1000000" in negative.output
    # minidrive's own goals are p1..p3: priority 1 would rank the errand above two laws
    above = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", T3, "--goal", f"{goal}:1")
    assert above.exit_code == 2
    assert "priority 1 ranks the goal above the program's standing goals p2" in above.output
    forced = invoke("step", PROGRAMS / "minidrive.tlp", "--percepts", T3, "--goal", f"{goal}:1",
                    "--force")
    assert forced.exit_code == 0 and "    1 g4       impasse" in forced.output, forced.output
