"""Output files and odd option values on the command line (a newcomer's trial): a file that
cannot be written, or whose suffix names no format the command writes, is one `Error:` line
naming the option, the path and why (exit 1) before any run starts; an OSError that still
escapes a command is one line too; a `--join` to a router that does not answer leaves
nothing behind; counts, durations and scales out of range are refused by their option; a
key expression's suggested repair is a valid one."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from tools.cli import _Group, cli

ROOT = Path(__file__).resolve().parents[2]
TELEO = str(Path(sys.executable).parent / "teleo")
FIGURE3 = ROOT / "scenarios" / "blocks_figure3.toml"
DRIVING = ROOT / "scenarios" / "driving_demo.toml"
PROGRAM = ROOT / "programs" / "blocks.tlp"


@pytest.fixture
def here(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """A working folder that also holds the runs (TELEO_RUN_DIR)."""
    monkeypatch.setenv("TELEO_RUN_DIR", str(tmp_path / "runs"))
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture(scope="module")
def recorded(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The record of a short simulated run of seed 000's Figure 3."""
    runs = tmp_path_factory.mktemp("recorded")
    done = subprocess.run([TELEO, "simulate", str(FIGURE3), "--cycles", "10", "--json"],
                          capture_output=True, text=True, timeout=120,
                          env={**os.environ, "TELEO_RUN_DIR": str(runs)}, cwd=runs)
    assert done.returncode in (0, 1), done.stderr
    return Path(json.loads(done.stdout)["record"])


def one_error(result, *words: str) -> str:
    """The one `Error:` line of a command that failed cleanly (exit 1, no traceback)."""
    assert result.exit_code == 1, result.output
    assert isinstance(result.exception, SystemExit), result.exception  # not an escaped error
    assert "Traceback" not in result.output
    errors = [line for line in result.output.splitlines() if line.startswith("Error:")]
    assert len(errors) == 1, result.output
    for word in words:
        assert word in errors[0], errors[0]
    return errors[0]


def unwritable(tmp_path: Path) -> list[str]:
    """Paths no command can write: under /proc (refused even to root), under a file."""
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder\n")
    return ["/proc/nope/out.json", str(blocker / "sub" / "out.json")]


OUTPUT_OPTIONS = [
    (["step", str(PROGRAM), "--percepts", os.devnull, "--save-state"], "--save-state", ""),
    (["simulate", str(FIGURE3), "--cycles", "10", "--trace"], "--trace", ""),
    (["simulate", str(FIGURE3), "--cycles", "10", "--render"], "--render", ".png"),
    (["simulate", str(FIGURE3), "--cycles", "10", "--learned-out"], "--learned-out", ""),
    (["simulate", str(FIGURE3), "--cycles", "10", "--plot"], "--plot", ".png"),
    (["launch", str(FIGURE3), "--cycles", "10", "--summary"], "--summary", ""),
    (["launch", str(FIGURE3), "--cycles", "10", "--render"], "--render", ".png"),
    (["launch", str(FIGURE3), "--cycles", "10", "--plot"], "--plot", ".png"),
    (["render", str(FIGURE3), "--steps", "1", "--out"], "--out", ".png"),
]


@pytest.mark.parametrize("args, option, suffix", OUTPUT_OPTIONS,
                         ids=[f"{a[0]} {o}" for a, o, _ in OUTPUT_OPTIONS])
def test_an_output_that_cannot_be_written_is_refused_before_the_run(args, option, suffix,
                                                                    here):
    for path in unwritable(here):
        path = str(Path(path).with_suffix(suffix)) if suffix else path
        result = CliRunner().invoke(cli, [*args, path])
        line = one_error(result, option, path)
        assert "folder" in line  # the reason: its folder cannot be created, or is a file
    assert not (here / "runs").exists()  # nothing ran: no run folder, no record


def test_a_plot_that_cannot_be_written_or_has_no_plot_suffix(recorded, here):
    runner = CliRunner()
    one_error(runner.invoke(cli, ["plot", str(recorded), "--out", "/proc/nope/p.png"]),
              "--out", "/proc/nope/p.png", "cannot be created")
    one_error(runner.invoke(cli, ["plot", str(recorded), "--out", "p.txt"]),
              "--out", "p.txt", ".png, .svg or .pdf", "'.txt'")
    drawn = runner.invoke(cli, ["plot", str(recorded), "--out", "deep/er/p.svg"])
    assert drawn.exit_code == 0, drawn.output
    assert (here / "deep" / "er" / "p.svg").read_text().lstrip().startswith("<?xml")
    assert sorted(p.name for p in here.iterdir()) == ["deep"]  # the check left no probe


@pytest.mark.parametrize("command", ["simulate", "launch"])
def test_a_plot_suffix_is_checked_before_the_run(command, here):
    done = subprocess.run([TELEO, command, str(FIGURE3), "--cycles", "10", "--plot", "x.txt"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 1 and "Traceback" not in done.stderr, done.stderr
    assert done.stderr.strip().splitlines() == [
        "Error: --plot: x.txt: expected a plot file ending in .png, .svg or .pdf, got '.txt'"]
    assert not (here / "runs").exists() and not (here / "x.txt").exists()


@pytest.mark.parametrize("command", ["simulate", "launch"])
def test_a_plot_without_the_record_it_draws_is_refused(command, here):
    done = CliRunner().invoke(cli, [command, str(FIGURE3), "--cycles", "10", "--plot", "p.png",
                                    "--no-record"])
    assert done.exit_code == 2 and "--plot draws the run record: leave out --no-record" in \
        done.output
    assert not (here / "runs").exists() and not (here / "p.png").exists()


def test_the_outputs_still_go_into_folders_that_are_not_there_yet(here):
    done = CliRunner().invoke(cli, ["simulate", str(FIGURE3), "--cycles", "10", "--trace",
                                    "a/t.jsonl", "--render", "b/c/r.png", "--learned-out",
                                    "d/l.tlp", "--plot", "e/p.png"])
    assert done.exit_code == 0, done.output
    assert len((here / "a" / "t.jsonl").read_text().splitlines()) == 10
    for made in ("b/c/r.png", "d/l.tlp", "e/p.png"):
        assert (here / made).stat().st_size > 0, made


def test_an_os_error_that_escapes_a_command_is_one_line(recorded, here):
    # the safety net of tools/cli.py, on a real command: the default plot file beside the
    # record is a folder, which matplotlib cannot write
    record = here / "run" / recorded.name
    record.parent.mkdir()
    record.write_bytes(recorded.read_bytes())
    (record.parent / "plot.png").mkdir()
    one_error(CliRunner().invoke(cli, ["plot", str(record)]), "plot.png")
    assert isinstance(cli, _Group)

    group = _Group()

    @group.command()
    def boom() -> None:
        raise PermissionError(13, "Permission denied", "/some/file")

    one_error(CliRunner().invoke(group, ["boom"]), "Error: /some/file: Permission denied")


def test_join_to_a_router_that_does_not_answer(here):
    with socket.socket() as probe:  # a port nobody listens on
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    run = f"cruise-{os.getpid()}"
    done = subprocess.run([TELEO, "launch", str(DRIVING), "--cycles", "10", "--join",
                           f"tcp/127.0.0.1:{port}", "--run", run],
                          capture_output=True, text=True, timeout=90)
    assert done.returncode == 1, done.stderr
    assert "Traceback" not in done.stderr
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: --join: "), lines
    assert f"tcp/127.0.0.1:{port}" in lines[0]
    assert not (here / "runs").exists() and not (here / "out").exists()
    left = []
    for proc in Path("/proc").glob("[0-9]*"):
        try:
            if run.encode() in (proc / "cmdline").read_bytes():
                left.append(proc.name)
        except OSError:
            continue
    assert left == []


@pytest.mark.parametrize("args, option", [
    (["echo", "agent/ME/actions", "--count", "0", "--seconds", "3"], "--count"),
    (["echo", "agent/ME/actions", "--count", "-1"], "--count"),
    (["echo", "agent/ME/actions", "--seconds", "0"], "--seconds"),
    (["record", "r.mcap", "--count", "0"], "--count"),
    (["record", "r.mcap", "--seconds", "-1"], "--seconds"),
    (["replay", "r.mcap", "--rate", "-1"], "--rate"),
    (["inspect", "--seconds", "-1"], "--seconds"),
    (["render", str(DRIVING), "--out", "r.png", "--steps", "-1"], "--steps"),
    (["render", str(DRIVING), "--out", "r.png", "--scale", "-1"], "--scale"),
    (["render", str(DRIVING), "--out", "r.png", "--scale", "0"], "--scale"),
    (["render", str(DRIVING), "--out", "r.gif", "--every", "0"], "--every"),
])
def test_values_out_of_range_are_refused_by_their_option(args, option, here):
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 2, result.output
    assert f"Invalid value for '{option}'" in result.output and "not in the range" in \
        result.output
    assert sorted(p.name for p in here.iterdir()) == []


@pytest.mark.parametrize("keyexpr, said, not_said", [
    ("bad//key**", "'*' stands alone in a chunk", "e.g."),
    ("/", "empty chunk", "e.g."),
    ("teleo//x", "e.g. 'teleo/x'", "stands alone"),
    ("a//b#", "'#' may not appear", "empty chunk"),
])
def test_a_bad_key_expression_is_never_given_an_invalid_repair(keyexpr, said, not_said):
    result = CliRunner().invoke(cli, ["echo", keyexpr])
    assert result.exit_code == 2, result.output
    assert said in result.output and not_said not in result.output, result.output
