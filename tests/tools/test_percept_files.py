"""The forms a percept file may take (docs/language.md, "Percept files"; issue 12, item 8):
a list, an object whose "percepts" is that list, or a saved `teleo echo` line; anything else
is refused saying which forms are accepted, never read as "no percepts"."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from bus import keys
from bus.codec import encode
from bus.messages import Beliefs, Envelope, Percepts
from tools.cli import cli
from tools.commands.bus import _json_line

ROOT = Path(__file__).resolve().parents[2]
BLOCKS = ROOT / "programs" / "blocks.tlp"
ROWS = [["table", "T", "xpos", 0, "ypos", 0, "height", 2], ["hand", "H1", "status", "empty"],
        ["block", "A", "xpos", 0, "ypos", 2, "height", 2],
        ["block", "B", "xpos", 0, "ypos", 4, "height", 2]]
ENV = Envelope(1, "r1", 4, "ME.perception", 1)


def infer(path: Path):
    return CliRunner().invoke(cli, ["infer", str(BLOCKS), "--percepts", str(path)])


def echo_line(msg) -> str:
    """A line exactly as `teleo echo` prints it for `msg` (the command's own formatter)."""
    key = keys.percepts("r1", "ME") if msg.KIND == "Percepts" else keys.beliefs("r1", "ME")
    return _json_line(key, 123, encode(msg))


@pytest.mark.parametrize("text", [
    json.dumps(ROWS),
    json.dumps({"percepts": ROWS}),
    echo_line(Percepts(ENV, "ME", tuple(ROWS))) + "\n",
])
def test_each_documented_form_gives_the_same_beliefs(tmp_path, text):
    path = tmp_path / "p.json"
    path.write_text(text)
    result = infer(path)
    assert result.exit_code == 0, result.output
    assert "(on B A)" in result.output.splitlines()


@pytest.mark.parametrize("text, problem", [
    ('{"a": 1}', "got an object with keys a"),
    (echo_line(Beliefs(ENV, "ME", (["on", "B", "A"],))), "got a Beliefs message"),
    ('{"percepts": "none"}', "got an object with keys percepts"),
    ((echo_line(Percepts(ENV, "ME", tuple(ROWS))) + "\n") * 3,
     "3 JSON lines (saved messages?): keep one"),
])
def test_anything_else_is_refused_with_the_accepted_forms(tmp_path, text, problem):
    path = tmp_path / "p.json"
    path.write_text(text)
    for command in ("infer", "step"):
        result = CliRunner().invoke(cli, [command, str(BLOCKS), "--percepts", str(path)])
        assert result.exit_code == 1, result.output
        assert problem in result.output
        assert str(path) in result.output
    assert "expected a list of percepts, an object whose \"percepts\"" in infer(path).output \
        or "JSON lines" in problem
