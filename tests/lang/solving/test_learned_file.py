"""Learned-skill files (agents/lang/solving/learned.py): written in program syntax with a
comment per skill, accepted by `teleo check PROGRAM LEARNED`, read back by --learned; a
malformed file is refused with file:line:col, a file for another program names the concept
this program does not define."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from agents.lang import Engine, ProgramError, load_program
from agents.lang.solving.learned import clause_heads, learned_text, read_learned
from tools.cli import cli

from ..conftest import PROGRAMS, ROOT, figure3_program
from ..test_blocks import TOWER, run

BLOCKS = ROOT / "programs" / "blocks.tlp"


@pytest.fixture(scope="module")
def learned() -> tuple[str, ...]:
    engine = Engine(figure3_program())
    return run(engine, engine.initial_state(), TOWER, cycles=6)[3].learned


@pytest.fixture()
def learned_file(tmp_path, learned):
    path = tmp_path / "learned-ME.tlp"
    path.write_text(learned_text(learned, "programs/blocks.tlp"))
    return path


def invoke(*args):
    return CliRunner().invoke(cli, [str(a) for a in args])


def test_the_file_reads_back_clause_by_clause_with_its_comments(learned, learned_file):
    text = learned_file.read_text()
    assert text.startswith("; teleo learned skills for programs/blocks.tlp\n")
    assert "; learned at cycle 3 from problem (clear A) (goal p1)" in text
    assert read_learned(load_program(BLOCKS), text, str(learned_file)) == learned
    assert clause_heads(text) == ["(unstackable ?b1 ?b2)", "(clear ?b1)"]


def test_teleo_check_accepts_program_and_learned_file(learned_file):
    result = invoke("check", BLOCKS, learned_file)
    assert result.exit_code == 0, result.output
    assert f"{learned_file}: ok (2 learned skills for {BLOCKS})" in result.output


def test_teleo_check_refuses_a_learned_file_for_another_program(learned_file):
    result = invoke("check", PROGRAMS / "minidrive.tlp", learned_file)
    assert result.exit_code == 1
    assert f"{learned_file}:6:2: undefined concept 'unstackable' in (unstackable ?b1 ?b2) " \
           "(head of skill unstackable#1)" in result.output


def test_teleo_check_alone_uses_the_program_the_first_line_names(learned_file, tmp_path,
                                                                  monkeypatch):
    monkeypatch.chdir(ROOT)   # the file names programs/blocks.tlp, as it was given the run
    result = invoke("check", learned_file)
    assert result.exit_code == 0, result.output
    assert f"{learned_file}: ok (2 learned skills for programs/blocks.tlp)" in result.output
    monkeypatch.chdir(tmp_path)   # where programs/blocks.tlp is not
    result = invoke("check", learned_file)
    assert result.exit_code == 1
    assert f"{learned_file}:1:1: learned with programs/blocks.tlp (its first line), which " \
           "does not load: programs/blocks.tlp: cannot read file: No such file or directory; " \
           "name the program before it (teleo check PROGRAM LEARNED)" in result.output


def test_a_malformed_learned_file_is_refused_with_file_line_col(tmp_path, learned):
    bad = tmp_path / "bad.tlp"
    text = learned_text(learned, "programs/blocks.tlp").replace(":start ((on ?b1 ?b2))",
                                                                ":start ((on ?b1 ?b2)")
    bad.write_text(text)
    with pytest.raises(ProgramError, match=rf"{bad}:6:1: '\(' is never closed"):
        read_learned(load_program(BLOCKS), text, str(bad))
    result = invoke("check", BLOCKS, bad)
    assert result.exit_code == 1 and f"{bad}:6:1:" in result.output
    assert "Traceback" not in result.output


def test_a_learned_file_holds_skills_only(tmp_path):
    text = "; teleo learned skills for x\n((clear ?b) :percepts ((block ?b)))\n"
    with pytest.raises(ProgramError, match=r"f.tlp:2:1: a learned file holds skill clauses"):
        read_learned(load_program(BLOCKS), text, "f.tlp")


def test_simulate_refuses_a_learned_file_for_another_program(learned_file):
    result = invoke("simulate", ROOT / "scenarios" / "driving_demo.toml", "--cycles", "1",
                    "--learned", learned_file)
    assert result.exit_code == 1
    assert f"{learned_file}:6:2: undefined concept 'unstackable'" in result.output
    assert "Traceback" not in result.output


def test_simulate_writes_the_learned_file(tmp_path):
    out = tmp_path / "out.tlp"
    result = invoke("simulate", ROOT / "scenarios" / "driving_demo.toml", "--cycles", "2",
                    "--learned-out", out, "--json")
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["learned"] == {"ME": {"file": str(out), "skills": []}}
    # the program as the scenario names it, found from any directory (an absolute path)
    assert out.read_text().splitlines()[0].startswith("; teleo learned skills for ")
    assert out.read_text().splitlines()[0].endswith("programs/driving.tlp")


def test_a_file_of_no_learned_skills_reads_back_empty(tmp_path):
    """What a run that learned nothing writes (a launch's learned-AGENT.tlp)."""
    empty = tmp_path / "learned-ME.tlp"
    empty.write_text(learned_text((), str(BLOCKS)))
    assert read_learned(load_program(BLOCKS), empty.read_text(), str(empty)) == ()
    result = invoke("check", BLOCKS, empty)
    assert result.exit_code == 0 and f"{empty}: ok (0 learned skills for {BLOCKS})" in \
        result.output, result.output
