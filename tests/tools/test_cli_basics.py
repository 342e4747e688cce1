"""The command's conventions (issue 12, item 11): --version, -h everywhere, summaries that are
whole first sentences (not cut at "e.g."), shell completion as the README documents it, and
one-line errors for bad bus inputs (item 1)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from tools.cli import cli, summary

TELEO = str(Path(sys.executable).parent / "teleo")


def invoke(*args: str):
    return CliRunner().invoke(cli, list(args), prog_name="teleo")


def test_version_and_short_help():
    from importlib.metadata import version

    assert invoke("--version").output == f"teleo {version('teleo')}\n"
    for args in (["-h"], ["goal", "-h"], ["goal", "post", "-h"], ["simulate", "-h"]):
        result = invoke(*args)
        assert result.exit_code == 0 and result.output.startswith("Usage: teleo"), args


def test_summaries_are_whole_sentences_not_cut_at_an_abbreviation():
    assert summary("Print X (e.g. 'a.b') as JSON. More here.") == "Print X (e.g. 'a.b') as JSON"
    assert summary("Inject JSON, e.g. '{}', i.e. an event; then more. Next.") == \
        "Inject JSON, e.g. '{}', i.e. an event; then more"
    assert summary("word " * 30).endswith("...") and len(summary("word " * 30)) <= 66
    listing = invoke("--help").output + invoke("goal", "--help").output
    for line in listing.splitlines():
        assert not line.rstrip().endswith(("e.g.", "(e.g", "e.g")), line
    assert "event     Inject a world event into the running launch; print its verdict" \
        in listing


def test_shell_completion_works_as_documented():
    script = subprocess.run([TELEO], env={**os.environ, "_TELEO_COMPLETE": "bash_source"},
                            capture_output=True, text=True, timeout=60)
    assert script.returncode == 0 and "complete " in script.stdout and "teleo" in script.stdout
    words = subprocess.run([TELEO], env={**os.environ, "_TELEO_COMPLETE": "bash_complete",
                                         "COMP_WORDS": "teleo go", "COMP_CWORD": "1"},
                           capture_output=True, text=True, timeout=60)
    assert "plain,goal" in words.stdout.splitlines()
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    assert 'eval "$(_TELEO_COMPLETE=bash_source teleo)"' in readme


@pytest.mark.parametrize("args, message", [
    (["echo", ""], "key expression must be a non-empty string"),
    (["echo", "teleo//x"], "empty chunk (a leading, trailing or double slash)"),
    (["echo", "teleo/a*"], "stands alone in a chunk"),
    (["record", "f.mcap", "--run", "*"], "run '*' contains forbidden character(s) '*'"),
])
def test_bad_bus_inputs_are_usage_errors_not_tracebacks(args, message, tmp_path):
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 2, result.output
    assert message in result.output and "Traceback" not in result.output
    assert not isinstance(result.exception, Exception) or isinstance(result.exception,
                                                                     SystemExit)


def test_a_router_on_a_busy_port_says_so_in_one_line():
    import socket

    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        done = subprocess.run([TELEO, "router", "--listen", f"tcp/127.0.0.1:{port}"],
                              capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    assert done.stderr.startswith(f"Error: cannot start a router listening on tcp/127.0.0.1:"
                                  f"{port}; the port is in use")
    assert "Traceback" not in done.stderr and len(done.stderr.splitlines()) == 1


def test_an_event_nested_too_deeply_is_one_line_naming_where():
    result = CliRunner().invoke(cli, ["event", '{"kind": ' + "[" * 5000 + "]" * 5000 + "}"])
    assert result.exit_code == 1
    assert result.output == "Error: JSON:1:73: nested deeper than 64 levels\n"


def test_a_bad_learned_entry_of_a_state_file_is_named_by_the_file_and_entry(tmp_path):
    """Issue 31 (drill n9): a bad skill in a `--state` file's "learned" was reported as
    `<learned>:1:60: ...`, naming no file."""
    import json

    program = str(Path(__file__).resolve().parents[2] / "tests" / "e2e" / "fixtures"
                  / "hold_speed.tlp")
    percepts, state = tmp_path / "p.txt", tmp_path / "s.json"
    percepts.write_text("(self ME speed 0 limit 20)\n")
    saved = invoke("step", program, "--percepts", str(percepts), "--save-state", str(state))
    assert saved.exit_code == 0, saved.output
    doc = json.loads(state.read_text())
    skill = "((at-desired-speed ?self) :percepts ((self ?self)) :start ((too-{}ow ?self)) " \
            ":actions ((*gas 10)))"
    doc["learned"] = [skill.format("sl"), skill.format("sl"), skill.format("s")]
    state.write_text(json.dumps(doc))
    done = invoke("step", program, "--percepts", str(percepts), "--state", str(state))
    assert done.exit_code == 1
    assert done.output.startswith(f"{state}: learned[2]:1:60: undefined concept 'too-sow'"), \
        done.output
