"""The readers' limits (docs/language.md, "Limits"): the fault drill's minimal cases (F7, F9)
give teleo's own error with file:line:col, never a Python exception."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from agents.lang import GoalError, ProgramError, load_program, load_program_text, parse_percepts
from agents.lang.core.limits import MAX_DEPTH, MAX_DIAGNOSTICS, MAX_TEXT_CHARS, read_json
from agents.lang.core.sexpr import read, to_text
from agents.lang.reading.goals import parse_goal

from .conftest import ROOT

TELEO = str(Path(sys.executable).parent / "teleo")
SPEED = "((fast ?x) :percepts ((self ?x speed ?s)) :tests ((> ?s {})))"


def program_errors(text: str) -> list[str]:
    with pytest.raises(ProgramError) as info:
        load_program_text(text, "p.tlp")
    return [str(d) for d in info.value.errors]


def percept_errors(text: str) -> list[str]:
    with pytest.raises(ProgramError) as info:
        parse_percepts(text, "p.txt")
    return [str(d) for d in info.value.errors]


def test_nesting_deeper_than_the_limit_is_an_error_at_the_parenthesis():
    # drill F7: 334 nested lists raised RecursionError
    assert program_errors("(" * 334 + ")" * 334) == [
        f"p.tlp:1:{MAX_DEPTH + 1}: lists nested deeper than {MAX_DEPTH} levels; reading stops "
        "here"]
    forms, diags = read("(" * MAX_DEPTH + ")" * MAX_DEPTH)
    assert len(forms) == 1 and diags == []


def test_long_numbers_and_tokens_are_refused_with_where_they_start():
    # drill F7: integers over 4300 digits raised ValueError
    assert program_errors(SPEED.format("1" * 5000)) == [
        "p.tlp:1:57: token 1111111111111111111111111111111111111111... (5000 characters) is "
        "longer than 256 characters"]
    assert program_errors(SPEED.format(2**63)) == [
        "p.tlp:1:57: 9223372036854775808: integer out of range (integers are signed 64-bit)"]
    assert program_errors(SPEED.format("1e999")) == [
        "p.tlp:1:57: 1e999: number inf is not finite (NaN and infinity are not values)"]
    assert load_program_text(SPEED.format(2**63 - 1), "p.tlp").arity == {"fast": 1}


@pytest.mark.parametrize("text, message", [
    ("[" * 5000 + "]" * 5000, "p.txt:1:65: nested deeper than 64 levels"),
    ('[["self", "ME", "speed", ' + "9" * 5000 + "]]",
     "p.txt:1:26: number of 5000 characters is longer than 256"),
    ('[["self", "ME", "speed", NaN]]',
     "p.txt:1:26: NaN is not a number teleo accepts (values are finite)"),
    ('[["self", "ME", "speed", -Infinity]]',
     "p.txt:1:26: -Infinity is not a number teleo accepts (values are finite)"),
    ('[["self", "ME", "speed", 1e400]]',
     "p.txt:1:26: 1e400: number inf is not finite (NaN and infinity are not values)"),
    ('[["self", "ME", "name", "\\ud800"]]',
     'p.txt:1:25: string "\\ud800" holds an escape that is not a character'),
    ("((self ME speed " + "1" * 5000 + "))",
     "p.txt:1:17: token 1111111111111111111111111111111111111111... (5000 characters) is longer "
     "than 256 characters"),
    ("((self ME speed 1e999))",
     "p.txt:1:17: 1e999: number inf is not finite (NaN and infinity are not values)"),
])
def test_percept_texts_within_the_limits(text, message):
    assert percept_errors(text) == [message]


def test_nan_and_inf_symbols_stay_symbols_in_s_expressions():
    (p,) = parse_percepts("((self ME mood nan level inf))")
    assert p.get("mood") == "nan" and p.get("level") == "inf"


def test_too_many_problems_stop_the_reader():
    forms, diags = read(")" * 10_000, "p.tlp")
    assert len(diags) == MAX_DIAGNOSTICS + 1
    assert diags[-1].message == f"more than {MAX_DIAGNOSTICS} problems; reading stops here"


def test_too_long_texts_are_not_read():
    text = "(a)" * (MAX_TEXT_CHARS // 3 + 1)
    assert program_errors(text) == [f"p.tlp:1:1: text of {len(text)} characters is longer than "
                                    f"the limit of {MAX_TEXT_CHARS}"]
    with pytest.raises(ProgramError, match="longer than the limit"):
        read_json("[" + "1," * MAX_TEXT_CHARS + "1]", "big.json")


def test_messages_show_a_bounded_form():
    forms, _ = read("(" + " x" * 10_000 + ")")
    text = to_text(forms[0])
    assert len(text) <= 204 and text.endswith(" ...")


def test_a_goal_of_a_concept_defined_with_two_arities_is_an_error_not_a_crash():
    # found by bench/faults/fuzz.py: goals.enumerable indexed past a shorter clause head
    errors = program_errors("(concepts ((c ?x) :percepts ((o ?x)))\n"
                            "          ((c ?x ?y) :percepts ((o ?x a ?y))))\n(goals (c ?p ?q))")
    assert errors[0].startswith("p.tlp:2:12: concept c defined with 2 argument(s) here but with "
                                "1 at p.tlp:1:12")


EMPTY = ("the file holds no forms (an empty program): expected (concepts ...), (skills ...) "
         "or (goals ...)")


@pytest.mark.parametrize("text", ["", "; only a comment\n", "  \n\n\t\n"])
def test_an_empty_program_is_an_error(text):
    """Issue 24, #17: it loaded with a warning, and a run of it "completed" 0 of 0 goals."""
    with pytest.raises(ProgramError) as info:
        load_program_text(text, "empty.tlp")
    assert str(info.value) == f"empty.tlp:1:1: {EMPTY}"
    with pytest.raises(ProgramError, match="an empty program"):   # every file of it empty
        load_program_text(text, "p.tlp", (text, "more.tlp"))
    program = load_program_text("(concepts ((a ?x) :percepts ((o ?x))))", "p.tlp",
                                (text, "more.tlp"))               # one file of several: a warning
    assert [str(w) for w in program.warnings] == [
        "more.tlp:1:1: warning: the file holds no forms (the program's other files do)"]


@pytest.mark.parametrize("goal, message", [
    ("(" * 100, "column 65: lists nested deeper than 64 levels"),
    ("(and" + " (package-delivered PACKET1)" * 2500 + ")", "longer than 65536 characters"),
    ("(package-delivered 1e999)", "column 20: 1e999: number inf is not finite"),
    ("(package-delivered " + "7" * 70000 + ")", "longer than 65536 characters"),
])
def test_goals_within_the_limits(goal, message):
    with pytest.raises(GoalError, match=message):
        parse_goal(goal)


def test_a_file_that_is_not_utf8_names_the_line_and_column_of_the_bad_byte(tmp_path):
    path = tmp_path / "latin1.tlp"
    path.write_bytes(b"((fast ?x)\n :percepts ((self ?x speed \xff\xfe))\n)\n")
    with pytest.raises(ProgramError) as info:
        load_program(path)
    assert str(info.value) == (f"{path}:2:28: not UTF-8: byte 0xff (invalid start byte); save "
                               "the file as UTF-8")


def test_a_byte_order_mark_is_skipped(tmp_path):
    path = tmp_path / "bom.tlp"
    path.write_bytes(b"\xef\xbb\xbf" + SPEED.format(10).encode())
    assert load_program(path).arity == {"fast": 1}


def test_a_file_over_the_limit_is_refused_unread(tmp_path):
    path = tmp_path / "big.tlp"
    path.write_bytes(b" " * (MAX_TEXT_CHARS + 1))
    with pytest.raises(ProgramError, match=f"file is larger than the limit of {MAX_TEXT_CHARS}"):
        load_program(path)


# -- the real `teleo check` and `teleo launch` on real files (drill F7) ---------------------

def teleo(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run([TELEO, *args], cwd=cwd, capture_output=True, text=True, timeout=120)


def test_teleo_check_reports_deep_nesting_and_bad_bytes_without_a_traceback(tmp_path):
    deep = tmp_path / "deep.tlp"
    deep.write_text("(" * 400 + ")" * 400 + "\n")
    latin = tmp_path / "latin1.tlp"
    latin.write_bytes(b"((fast ?x)\n :percepts ((self ?x speed \xff\xfe))\n)\n")
    digits = tmp_path / "digits.tlp"
    digits.write_text(SPEED.format("1" * 5000) + "\n")
    done = teleo("check", str(deep), str(latin), str(digits))
    assert done.returncode == 1
    assert "Traceback" not in done.stderr
    assert done.stderr.splitlines() == [
        f"{deep}:1:65: lists nested deeper than 64 levels; reading stops here",
        f"{deep}: 1 error",
        f"{latin}:2:28: not UTF-8: byte 0xff (invalid start byte); save the file as UTF-8",
        f"{latin}: 1 error",
        f"{digits}:1:57: token 1111111111111111111111111111111111111111... (5000 characters) is "
        "longer than 256 characters",
        f"{digits}: 1 error"]


def test_teleo_check_refuses_an_empty_program(tmp_path):
    empty = tmp_path / "empty.tlp"
    empty.write_text("")
    done = teleo("check", str(empty))
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert done.stderr.splitlines() == [f"{empty}:1:1: {EMPTY}", f"{empty}: 1 error"]


def test_teleo_launch_refuses_a_program_that_is_not_utf8_before_starting(tmp_path):
    fixtures = ROOT / "tests" / "e2e" / "fixtures"
    (tmp_path / "hold_speed.tlp").write_bytes(b"(concepts\n  ((a ?x) :percepts ((o ?x \xe9))))\n")
    scenario = tmp_path / "s.toml"
    scenario.write_text((fixtures / "hold_speed.toml").read_text())
    done = subprocess.run([TELEO, "launch", str(scenario)], cwd=ROOT, capture_output=True,
                          text=True, timeout=120, env={"TELEO_RUN_DIR": str(tmp_path),
                                                       "PATH": "/usr/bin:/bin"})
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert f"{tmp_path / 'hold_speed.tlp'}:2:28: not UTF-8: byte 0xe9" in done.stderr
    assert not (tmp_path / "runs").exists()  # nothing was started
