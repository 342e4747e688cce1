"""`teleo check SCENARIO` checks a scenario fully before anything runs (issue 12, item 5), and
scenario files that are not text, nested too deep or hold values no message can carry are
refused with file:line:col or the key, never a traceback (item 1)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from click.testing import CliRunner

from tools.cli import cli
from tools.commands.check import is_scenario
from tools.commands.scenario_check import load_checked
from world.run_scenario import ScenarioError, load_scenario

ROOT = Path(__file__).resolve().parents[2]
DEMO = (ROOT / "scenarios" / "driving_demo.toml").read_text()
DRIVING = ROOT / "programs" / "driving.tlp"


def scenario(tmp_path: Path, text: str, name: str = "s.toml") -> Path:
    path = tmp_path / name
    path.write_text(text.replace('"programs/driving.tlp"', f'"{DRIVING}"'))
    return path


def invoke(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


@pytest.mark.parametrize("change, message", [
    (("address = 6,", "address = 99,"), r"\[world\] package PACKET1: no address 99 on B"),
    (('goal = "(package-delivered PACKET1)"', 'goal = "(flying ME)"'),
     r"\[\[goals\]\] #1: goal \(flying ME\): undefined concept 'flying'"),
    (("priority = 5\nat_cycle = 0", "priority = 1\nat_cycle = 0"),
     r"\[\[goals\]\] #1: priority 1 ranks the goal above the program's standing goal p2"),
    (("priority = 5\nat_cycle = 0", "priority = 0\nat_cycle = 0"),
     r"\[\[goals\]\] #1: priority: expected an integer in 1..1000000, got 0"),
    (('id = "PACKET2"', 'id = "PACKET 2"'), r"\[world\] package 'PACKET 2': expected an id"),
    (('owner = "ME" },  #', 'owner = "YOU" },  #'),
     r"package PACKET2: owner 'YOU' is not an agent of this run"),
    (('cars = [{ agent = "ME"', 'cars = [{ agent = "YOU"'),   # ME would start elsewhere
     r"\[world\] cars: 'YOU' is not an agent of this run \(agents: ME\)"),
])
def test_every_part_of_a_scenario_is_checked_before_it_runs(tmp_path, change, message):
    path = scenario(tmp_path, DEMO.replace(*change))
    with pytest.raises(ScenarioError, match=message):
        load_checked(path)
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert result.output.count("\n") == 1, result.output        # one line, not 219


def test_a_goal_above_the_laws_is_accepted_when_the_scenario_forces_it(tmp_path):
    path = scenario(tmp_path, DEMO.replace("priority = 5\nat_cycle = 0",
                                           "priority = 2\nforce = true\nat_cycle = 0"))
    loaded, _ = load_checked(path)
    assert loaded.goals[0].force and loaded.goals[0].priority == 2


def test_an_unknown_event_kind_is_an_error_for_each_domain(tmp_path):
    path = scenario(tmp_path, DEMO + '\n[[events]]\nat_cycle = 3\nkind = "teleport"\n')
    with pytest.raises(ScenarioError, match=r"#1.kind: expected one of \['pedestrian', "):
        load_checked(path)
    blocks = (ROOT / "scenarios" / "blocks_figure3.toml").read_text().replace(
        '"programs/blocks.tlp"', f'"{ROOT / "programs" / "blocks.tlp"}"')
    path = scenario(tmp_path, blocks + '\n[[events]]\nat_cycle = 3\nkind = "teleport"\n', "b.toml")
    with pytest.raises(ScenarioError, match=r"kind: expected one of \[.*got 'teleport'"):
        load_checked(path)


@pytest.mark.parametrize("event, message", [
    ('kind = "pedestrian"\nahead_of = "ME"\ndist = 20\ncolour = "red"',
     r"\[\[events\]\] #1 \(pedestrian\): unknown field 'colour'; known: kind, ahead_of"),
    ('kind = "package"\nid = "P9"\naddress = 3\nstreet = "B"\nowner = ["ME"]',
     r"\[\[events\]\] #1 \(package\): owner: expected an agent's name, got \['ME'\]"),
    ('kind = "block"', r"\[\[events\]\] #1 \(block\): segment: missing; expected a segment"),
])
def test_a_scripted_events_fields_are_checked_as_the_world_checks_them(tmp_path, event,
                                                                      message):
    """Issue 24, items 1-2: `teleo check` refuses an [[events]] field the world would refuse
    (an unknown one, as it does for every other table's unknown key), before the run."""
    path = scenario(tmp_path, DEMO + f"\n[[events]]\nat_cycle = 3\n{event}\n")
    with pytest.raises(ScenarioError, match=message):
        load_checked(path)
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output


def test_check_recognises_scenarios_and_checks_every_shipped_one():
    shipped = sorted((ROOT / "scenarios").glob("*.toml"))
    result = CliRunner().invoke(cli, ["check", *map(str, shipped)], catch_exceptions=False)
    assert result.exit_code == 0, result.output
    assert result.output.count(": ok (scenario, ") == len(shipped)
    assert "driving_demo.toml: ok (scenario, driving world; agents ME (programs/driving.tlp)" \
        in result.output


def test_a_scenario_without_the_toml_suffix_is_recognised_by_its_text(tmp_path):
    path = scenario(tmp_path, "# a scenario\n\n" + DEMO, "demo.scenario")
    assert is_scenario(str(path)) and not is_scenario(str(DRIVING))
    result = invoke("check", path)
    assert result.exit_code == 0 and ": ok (scenario, driving world" in result.output


def test_check_json_gives_each_files_verdict_and_errors(tmp_path):
    bad = scenario(tmp_path, DEMO.replace("address = 6,", "address = 99,"))
    result = invoke("check", "--json", DRIVING, bad)
    assert result.exit_code == 1
    doc = json.loads(result.output)
    assert doc["ok"] is False
    program, scen = doc["files"]
    assert (program["kind"], program["ok"], program["goals"]) == ("program", True, 2)
    assert (scen["kind"], scen["ok"]) == ("scenario", False)
    assert "no address 99 on B" in scen["errors"][0]["message"]
    broken = tmp_path / "broken.tlp"
    broken.write_text("(concepts ((a ?x) :percepts ((o ?x)) :relations ((b ?x)))))")
    doc = json.loads(invoke("check", "--json", broken).output)
    error = doc["files"][0]["errors"][0]
    assert (error["file"], error["line"], error["col"]) == (str(broken), 1, 50)
    assert error["message"].startswith("undefined concept 'b'")


@pytest.mark.parametrize("data, message", [
    (b'[run]\nname = "x\xff"\n', r"s.toml:2:10: not UTF-8: byte 0xff"),
    (b"a = " + b"[" * 5000 + b"]" * 5000, r"s.toml:1:37: arrays or inline tables nested "
                                          r"deeper than 32 levels"),
    (b"[run]\ndeadline = nan\n", r"\[run\].deadline: expected a finite number, got nan"),
    (b'[[events]]\nat_cycle = 1\nkind = "block"\nsegment = "S1"\nspeed = inf\n',
     r"\[\[events\]\] #1.speed: expected a finite number, got inf"),
    (b"[[events]]\nat_cycle = 1\nwhen = 1979-05-27\n", r"#1.when: expected a string, number"),
    (b"[run]\nseed = 99999999999999999999\n", r"\[run\].seed: integer out of range"),
    (b"[run]\ncycles = 1\n" + b"# " + b"x" * (1 << 20) + b"\n", r"longer than the limit"),
    # found by bench/faults/fuzz.py's scenario reader: Python refuses to convert the number
    (b"[run]\nseed = " + b"9" * 5000 + b"\n", r"an integer of more than 4300 digits"),
])
def test_hostile_scenario_files_get_one_line_naming_where(tmp_path, data, message):
    path = tmp_path / "s.toml"
    path.write_bytes(data)
    with pytest.raises(ScenarioError, match=message):
        load_scenario(path)
    for command in ("check", "simulate", "launch"):
        result = invoke(command, path)
        assert result.exit_code != 0 and "Traceback" not in result.output, result.output
        assert not isinstance(result.exception, (RecursionError, UnicodeDecodeError))


def test_nesting_inside_strings_and_comments_is_not_counted(tmp_path):
    path = scenario(tmp_path, DEMO.replace("[run]", '[run]\n# ' + "[" * 100 + "\n")
                    .replace('name = "driving-demo"', 'name = "' + "{" * 60 + '"'))
    assert load_scenario(path).run.name == "{" * 60


def test_a_program_path_too_long_to_look_up_is_not_found(tmp_path):
    """Found by bench/faults/fuzz.py: a name over the system's limit raised OSError from pathlib."""
    path = scenario(tmp_path, DEMO.replace('"programs/driving.tlp"',
                                           '"programs/driving.' + "7" * 400 + 'tlp"'))
    with pytest.raises(ScenarioError, match="program programs/driving.777.* not found"):
        load_checked(path)
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output


def test_an_action_the_world_does_not_know_is_refused_with_its_place(tmp_path):
    """The world would fail (*fly 6.25) every cycle, and the run would say it completed."""
    program = tmp_path / "flying.tlp"
    text = DRIVING.read_text()
    program.write_text(text.replace("(*gas 6.25)", "(*fly 6.25)", 1))
    line = text[:text.index("(*gas 6.25)")].count("\n") + 1
    path = scenario(tmp_path, DEMO.replace('"programs/driving.tlp"', f'"{program}"'))
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert f"agent ME: {program}:{line}:" in result.output
    assert "action *fly is not one the driving world knows (*cruise *gas *brake *straighten " \
           "*steer)" in result.output


def test_a_scripted_cancel_must_name_a_goal_the_scenario_has_posted_by_then(tmp_path):
    cancel = '\n[[goals]]\nop = "cancel"\ngoal_id = "{}"\nforce = true\nat_cycle = {}\n'
    path = scenario(tmp_path, DEMO + cancel.format("g2", 100))   # g2 is posted at cycle 150
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert "[[goals]] #3: goal_id 'g2': the scenario has posted no such goal by cycle 100 " \
           "(its posts get g1, g2, ... in order; by then: g1)" in result.output
    load_checked(scenario(tmp_path, DEMO + cancel.format("g2", 200), "later.toml"))


def test_a_scenario_goal_may_be_a_conjunction_and_a_bad_one_is_refused(tmp_path):
    """issue 22: [[goals]] goal = "(and ...)" is checked as teleo goal post checks it."""
    blocks = (ROOT / "scenarios" / "blocks_figure3.toml").read_text().replace(
        '"programs/blocks.tlp"', f'"{ROOT / "programs" / "blocks.tlp"}"')
    good = scenario(tmp_path, blocks.replace('goal = "(clear A)"',
                                             'goal = "(and (on C A) (on A B))"'), "c.toml")
    loaded, _ = load_checked(good)
    assert loaded.goals[0].goal == "(and (on C A) (on A B))"
    bad = scenario(tmp_path, blocks.replace('goal = "(clear A)"',
                                            'goal = "(and (on C A) (onn A B))"'), "d.toml")
    with pytest.raises(ScenarioError, match=r"undefined concept 'onn' \(conjunct \(onn A B\)\)"):
        load_checked(bad)


# -- the 2026-12-02 trial's defects (issue 24, #2, #8, #9, #17) -------------------------------

@pytest.mark.parametrize("name", ["../../etc/x y", "a/b", "x y", "", "a\nb", "a*b", "n" * 65])
def test_a_run_name_that_cannot_name_keys_and_a_folder_is_refused_by_check(tmp_path, name):
    """#2: check said ok, simulate crashed with a traceback after making a folder outside
    out/runs, launch blamed a --run option nobody gave."""
    path = scenario(tmp_path, DEMO.replace('name = "driving-demo"', f"name = {json.dumps(name)}"))
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    shown = repr(name) if len(repr(name)) <= 60 else repr(name)[:57] + "..."  # cut at 60
    assert result.output == (f"{path}: [run].name: expected a name of at most 64 characters "
                             "without spaces, control characters or any of / * $ ? # @ (it "
                             f"names the run's bus keys and folder), got {shown}\n")


@pytest.mark.parametrize("command", ["simulate", "launch"])
def test_simulate_and_launch_of_such_a_name_write_nothing_anywhere(tmp_path, monkeypatch,
                                                                    command):
    work = tmp_path / "deep" / "w"
    work.mkdir(parents=True)
    path = scenario(tmp_path, DEMO.replace('name = "driving-demo"', 'name = "../../etc/x y"'))
    monkeypatch.chdir(work)
    monkeypatch.delenv("TELEO_RUN_DIR", raising=False)
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(tmp_path / "xdg"))
    result = invoke(command, path, "--cycles", "3")
    assert result.exit_code == 1 and "Traceback" not in result.output, result.output
    assert result.output.startswith(f"Error: {path}: [run].name: expected a name of at most")
    assert "--run" not in result.output
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == [
        Path("deep"), Path("deep/w"), Path("s.toml")]      # nothing written, here or above


def test_launch_names_the_option_or_the_field_a_bad_run_id_came_from(tmp_path, monkeypatch):
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    result = invoke("launch", scenario(tmp_path, DEMO), "--run", "a b")
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert result.output == "Error: --run: run id 'a b' contains forbidden character(s) ' '\n"


def test_check_reports_every_error_of_a_scenario_at_once(tmp_path):
    """#8: only the first error was reported; the next showed after mending it."""
    bad = scenario(tmp_path, DEMO.replace('street = "B", from', 'street = "Z", from')
                   .replace('goal = "(package-delivered PACKET1)"', 'goal = "(cruising ME"'))
    result = invoke("check", bad)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert result.output.splitlines() == [
        f"{bad}: [world] car ME: unknown street 'Z'",
        f"{bad}: [[goals]] #1: goal '(cruising ME': column 1: '(' is never closed (missing ')')",
        f"{bad}: 2 errors"]
    agents = DEMO[DEMO.index("[[agents]]"):DEMO.index("[[goals]]")]
    typo = scenario(tmp_path, DEMO.replace("[run]\n", "[run]\ntypo_key = 1\n")
                    .replace("[[goals]]", agents + "[[goals]]", 1), "typo.toml")
    doc = json.loads(invoke("check", "--json", typo).output)
    assert [e["message"] for e in doc["files"][0]["errors"]] == [
        f"{typo}: [run]: unknown field(s) ['typo_key']; expected ['cycles', 'deadline', "
        "'goals_respawn', 'mode', 'name', 'render_every', 'secure', 'seed', 'status']",
        f"{typo}: [[agents]]: agent ids must be unique, got ['ME', 'ME']"]


def test_what_follows_from_an_error_is_not_reported_again(tmp_path):
    """A goal of an agent whose entry is wrong is not checked against a program it has not."""
    bad = scenario(tmp_path, DEMO.replace('program = "', 'program = 7\nx = "', 1)
                   .replace("[[goals]]", '[[goals]]\nop = "cancel"\ngoal_id = "g9"', 1))
    with pytest.raises(ScenarioError) as info:
        load_checked(bad)
    assert info.value.errors[:2] == (
        f"{bad}: [[agents]] #1: unknown field(s) ['x']; expected ['id', 'mechanism', "
        "'program', 'respawn', 'solver']",
        f"{bad}: [[agents]] #1.program: expected str, got 7")
    assert len(info.value.errors) == 3 and "[[goals]] #1" in info.value.errors[2]


@pytest.mark.parametrize("field, value, message", [
    ("cycles", "-5", "[run].cycles: expected >= 0, got -5"),
    ("deadline", "0", "[run].deadline: expected > 0 [s], got 0"),
    ("deadline", "-0.5", "[run].deadline: expected > 0 [s], got -0.5"),
    ("render_every", "0", "[run].render_every: expected >= 1, got 0"),
    ("goals_respawn", "-1", "[run].goals_respawn: expected >= 0, got -1"),
    ("seed", "1.5", "[run].seed: expected int, got 1.5"),
    ("cycles", '"many"', "[run].cycles: expected int, got 'many'"),
    ("secure", "1", "[run].secure: expected true or false, got 1"),
    ("mode", '"fast"', "[run].mode: expected 'lockstep' or 'realtime', got 'fast'"),
])
def test_each_run_field_in_error_names_itself_and_its_value(tmp_path, field, value, message):
    """#9: `[run]: expected cycles >= 0, deadline > 0 [s], render_every >= 1` named neither."""
    run = DEMO[DEMO.index("[run]"):DEMO.index("[world]")]
    lines = [line for line in run.splitlines() if not line.startswith(f"{field} =")]
    path = scenario(tmp_path, DEMO.replace(run, "\n".join([*lines, f"{field} = {value}", ""])))
    result = invoke("check", path)
    assert result.exit_code == 1 and "Traceback" not in result.output
    assert result.output == f"{path}: {message}\n"


@pytest.mark.parametrize("text, message", [
    ("run = 5\n", "[run]: expected a table, got 5"),
    ("agents = 5\n", "[[agents]]: expected an array of tables ([[agents]] entries), got 5"),
    ("agents = [5]\n", "[[agents]] #1: expected a table, got 5"),
    ("goals = 3\n[[agents]]\nid = \"ME\"\nprogram = \"x.tlp\"\n",
     "[[goals]]: expected an array of tables"),
    ("world = 1\n[[agents]]\nid = \"ME\"\nprogram = \"x.tlp\"\n",
     "[world]: expected a table, got 1"),
    ("[[events]]\nat_cycle = -1\nkind = \"block\"\n", "[[events]] #1.at_cycle: expected >= 0, "
                                                     "got -1"),
    ("[[agents]]\nid = \"M E\"\nprogram = \"x.tlp\"\n", "[[agents]] #1.id: expected an id "
                                                        "without spaces"),
])
def test_tables_of_the_wrong_shape_are_an_error_not_a_traceback(tmp_path, text, message):
    path = tmp_path / "s.toml"
    path.write_text(text)
    with pytest.raises(ScenarioError, match=re.escape(message)):
        load_checked(path)
    for command in ("check", "simulate"):
        result = invoke(command, path)
        assert result.exit_code == 1 and "Traceback" not in result.output, result.output


def test_a_scenario_whose_program_is_empty_is_refused(tmp_path, monkeypatch):
    """#17: an empty program was accepted with exit 0, and its run 'completed' 0 of 0."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    empty = tmp_path / "empty.tlp"
    empty.write_text("; nothing yet\n")
    path = scenario(tmp_path, DEMO[:DEMO.index("[[goals]]")].replace(str(DRIVING), str(empty))
                    .replace('"programs/driving.tlp"', f'"{empty}"'))
    for command in ("check", "simulate"):
        result = invoke(command, path)
        assert result.exit_code == 1 and "Traceback" not in result.output, result.output
        assert f"agent ME: program {empty}:\n{empty}:1:1: the file holds no forms (an empty " \
               "program)" in result.output
    assert not (tmp_path / "runs").exists()


def test_schema_errors_do_not_hide_the_world_and_goal_errors(tmp_path):
    """Issue 31 (N14): an unknown [world] key hid the unknown street after it, and a goal
    whose agent was missing hid the goal's own syntax error; a concept misspelt in a
    scenario's goal gets the "did you mean" a program's error has."""
    agents = DEMO[DEMO.index("[[agents]]"):DEMO.index("[[goals]]")]
    text = (DEMO.replace("[run]\n", "[run]\ntypo_key = 1\n")
            .replace("pedestrians = 12", "pedestrains = 3")
            .replace('street = "B", from', 'street = "Z", from')
            .replace('agent = "ME"\ngoal = "(package-delivered PACKET1)"',
                     'goal = "(package-delivered PACKET1"')
            .replace('goal = "(package-delivered PACKET2)"', 'goal = "(package-delivred ME)"')
            .replace("[[goals]]", agents.replace('"ME"', '"YOU"') + "[[goals]]", 1))
    bad = scenario(tmp_path, text.replace(
        'cars = [{ agent = "ME", street = "Z", from = "FIRST", toward = "SECOND", along = 20.0 }]',
        'cars = [{ agent = "ME", street = "Z", from = "FIRST", toward = "SECOND", along = 20.0 },'
        ' { agent = "YOU", street = "A", from = "FIRST", toward = "SECOND", along = 5.0 }]'))
    lines = invoke("check", bad).output.splitlines()
    assert f"{bad}: [world] car ME: unknown street 'Z'" in lines, lines
    assert any(x.startswith(f"{bad}: [world] unknown keys ['pedestrains']") for x in lines)
    assert f"{bad}: [[goals]] #1.agent: required, expected str" in lines
    assert f"{bad}: [[goals]] #1: goal '(package-delivered PACKET1': column 1: '(' is never " \
           "closed (missing ')')" in lines
    assert f"{bad}: [[goals]] #2: goal (package-delivred ME): undefined concept " \
           "'package-delivred' (did you mean 'package-delivered'?)" in lines


def test_check_warns_of_a_goal_naming_an_object_the_world_has_not(tmp_path):
    """Issue 31 (N12): `(delivered mail-reid r-5399)` passed check (there is no r-5399) and
    failed 130 cycles into the run; check warns, naming the goal and the object, and says
    nothing of a goal whose objects all exist."""
    text = (ROOT / "scenarios" / "office_errand.toml").read_text().replace(
        '"programs/office_errand.tlp"', f'"{ROOT}/programs/office_errand.tlp"')
    good = scenario(tmp_path, text, "good.toml")
    result = invoke("check", good)
    assert result.exit_code == 0 and "warning" not in result.output, result.output
    bad = scenario(tmp_path, text.replace("(delivered mail-reid reid)",
                                          "(delivered mail-reid r-5399)"), "bad.toml")
    result = invoke("check", bad)
    assert result.exit_code == 0, result.output
    assert f"{bad}: warning: [[goals]] #1: goal (delivered mail-reid r-5399): no object " \
           "'r-5399' in the office world as it starts, nor in ME's program (the goal would " \
           "wait for a percept of it, then fail)" in result.output.splitlines()
    assert "'mail-reid'" not in result.output


def test_a_misspelt_world_is_the_one_error_not_the_default_worlds_actions_too(tmp_path):
    """A [world] in error is read as the default (driving) world; the blocks program's
    actions must not then be refused as unknown to driving: one error, the domain's."""
    path = scenario(tmp_path, '[world]\ndomain = "ofice"\n\n[[agents]]\nid = "ME"\n'
                              f'program = "{ROOT / "programs" / "blocks.tlp"}"\n')
    with pytest.raises(ScenarioError) as err:
        load_checked(str(path))
    assert len(err.value.errors) == 1, err.value.errors
    assert "did you mean 'office'" in err.value.errors[0]
