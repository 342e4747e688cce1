"""Bad input to the bus tools, refused before anything runs with one clear line and a non-zero
exit, never a traceback: `teleo record`'s file (the 2026-12-02 trial, #11: a missing folder
was made silently, a .txt name took MCAP without a word, /proc got a reason that contradicted
itself), and the options of `goal post --wait`, `echo --list`, `hz` and `replay`."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from tools.cli import cli

ROOT = Path(__file__).resolve().parents[2]
TELEO = str(Path(sys.executable).parent / "teleo")
HOLD_SPEED = ROOT / "tests" / "e2e" / "fixtures" / "hold_speed.toml"


@pytest.fixture
def here(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder that also holds the runs (TELEO_RUN_DIR): no launch runs there."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    monkeypatch.chdir(tmp_path)
    return tmp_path


def one_line(result, code: int) -> str:
    """The one `Error:` line of a command that failed cleanly with exit `code`."""
    assert result.exit_code == code, result.output
    assert isinstance(result.exception, SystemExit), result.exception
    assert "Traceback" not in result.output
    errors = [line for line in result.output.splitlines() if line.startswith("Error:")]
    assert len(errors) == 1, result.output
    return errors[0]


def test_record_refuses_a_folder_that_is_not_there_and_makes_none(here):
    line = one_line(CliRunner().invoke(cli, ["record", str(here / "no" / "dir" / "x.mcap"),
                                             "--seconds", "1"]), 1)
    assert line == (f"Error: FILE: cannot write {here}/no/dir/x.mcap: its folder {here}/no/dir "
                    f"does not exist (create it first: mkdir -p {here}/no/dir)")
    assert sorted(p.name for p in here.iterdir()) == []


@pytest.mark.parametrize("name", ["x.txt", "x", "x.mcap.bak"])
def test_record_refuses_a_name_that_is_not_mcap(here, name):
    line = one_line(CliRunner().invoke(cli, ["record", name, "--seconds", "1"]), 1)
    assert line.startswith(f"Error: FILE: {name}: expected a run record file ending in .mcap, "
                           f"got '")
    assert sorted(p.name for p in here.iterdir()) == []


def test_record_into_a_folder_that_takes_no_file_gives_one_consistent_reason(here):
    # as root the folder's bits say "writable"; creating a file there fails all the same
    line = one_line(CliRunner().invoke(cli, ["record", "/proc/x.mcap", "--seconds", "1"]), 1)
    assert line.startswith("Error: FILE: cannot write /proc/x.mcap: no file can be created in "
                           "its folder /proc (")
    assert "not writable" not in line


def test_a_record_file_that_is_fine_gets_as_far_as_finding_the_launch(here):
    line = one_line(CliRunner().invoke(cli, ["record", "x.mcap", "--seconds", "1"]), 1)
    assert "no running teleo launch found" in line
    assert not (here / "x.mcap").exists()


def test_record_refuses_to_replace_a_file_without_force(here):
    """Trial 2026-12-04 N9: a 3 s record was replaced by a 1 s one without a word."""
    (here / "x.mcap").write_bytes(b"an earlier record")
    line = one_line(CliRunner().invoke(cli, ["record", "x.mcap", "--seconds", "1"]), 1)
    assert line == ("Error: record: writing x.mcap: it exists already; give another file, or "
                    "--force to replace it")
    assert (here / "x.mcap").read_bytes() == b"an earlier record"
    line = one_line(CliRunner().invoke(cli, ["record", "x.mcap", "--seconds", "1", "--force"]),
                    1)
    assert "no running teleo launch found" in line   # past the check, to the bus


BAD = [
    (["goal", "post", "(x)", "--timeout", "5"], 2, "--timeout goes with --wait"),
    (["goal", "post", "(x)", "--cancel-on-interrupt"], 2, "--cancel-on-interrupt goes with "
                                                          "--wait"),
    (["goal", "post", "(x)", "--wait", "--timeout", "0"], 2, "Invalid value for '--timeout'"),
    (["goal", "post", "(x)", "--wait", "--timeout", "-3"], 2, "Invalid value for '--timeout'"),
    (["goal", "post", "(x)", "--wait", "--timeout", "soon"], 2, "'soon' is not a valid float"),
    (["echo", "--list", "--count", "3"], 2, "--count goes with printing messages, not with "
                                            "--list"),
    (["echo", "--list", "--filter", "x"], 2, "--filter goes with printing messages"),
    (["echo", "--json"], 2, "--json goes with --list"),
    (["echo", "--list", "--seconds", "0"], 2, "Invalid value for '--seconds'"),
    (["echo", "--list", "a//b"], 2, "empty chunk"),
    (["hz"], 2, "Missing argument 'KEYEXPR'"),
    (["hz", "world/state", "--window", "1"], 2, "Invalid value for '--window'"),
    (["hz", "world/state", "--seconds", "-1"], 2, "Invalid value for '--seconds'"),
    (["hz", "bad**"], 2, "'*' stands alone in a chunk"),
    (["replay", "r.mcap", "--start", "-1"], 2, "Invalid value for '--start'"),
    (["replay", "r.mcap", "--rate", "-1"], 2, "Invalid value for '--rate'"),
    (["goal", "post", "(x)", "--wait"], 1, "no running teleo launch found"),
    (["hz", "world/state"], 1, "no running teleo launch found"),
    (["echo", "--list"], 1, "no running teleo launch found"),
]


@pytest.mark.parametrize("args, code, said", BAD, ids=[" ".join(a) for a, _, _ in BAD])
def test_bad_options_of_the_new_tools_are_one_line(args, code, said, here):
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == code, result.output
    assert said in result.output and "Traceback" not in result.output, result.output


@pytest.fixture(scope="module")
def record(tmp_path_factory) -> Path:
    runs = tmp_path_factory.mktemp("rec")
    done = subprocess.run([TELEO, "simulate", str(HOLD_SPEED), "--json"], capture_output=True,
                          text=True, timeout=120, cwd=runs,
                          env={**os.environ, "TELEO_RUN_DIR": str(runs)})
    assert done.returncode == 0, done.stderr
    return Path(json.loads(done.stdout)["record"])


def test_replay_refuses_a_start_past_the_record_and_paused_without_a_terminal(record, here):
    line = one_line(CliRunner().invoke(cli, ["replay", str(record), "--start", "30"]), 2)
    assert f"{record}: the record holds cycles 0..29, got 30" in line
    line = one_line(CliRunner().invoke(cli, ["replay", str(record), "--paused"]), 2)
    assert "--paused needs a terminal on stdin" in line
    assert not (here / "runs").exists()
