"""docs/tutorial.md runs as written (issue 12, item 15; issue 24, #13): its files are written,
its commands run in order in one shell in an empty folder, and each block of expected output
is exactly what the commands of the block before it printed, line for line: `...` within a
line stands for what changes from run to run, and a line of `...` alone for lines left out."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "docs" / "tutorial.md"
FENCE = re.compile(r"^```([^\n]*)\n(.*?)^```$", re.M | re.S)
MARK = "@@tutorial-block-{}@@"


def blocks(text: str) -> list[tuple[str, str, str]]:
    """(kind, file name or "", body) of each fenced block: a file to write ("tlp cruise.tlp"),
    commands ("sh") or expected output ("text")."""
    out = []
    for info, body in FENCE.findall(text):
        words = info.split()
        kind = words[0] if words else ""
        out.append((kind, words[1] if len(words) > 1 else "", body))
    return out


def script(parts: list[tuple[str, str, str]]) -> str:
    """One bash script: the files written, each block of commands after a marker line (so
    its output can be told apart), stderr into stdout in the order printed."""
    lines = ["set -e", "exec 2>&1"]
    for k, (kind, name, body) in enumerate(parts):
        if name:
            lines += [f"cat > {name} <<'TUTORIAL_EOF'", body.rstrip("\n"), "TUTORIAL_EOF"]
        elif kind == "sh":
            lines += [f"echo '{MARK.format(k)}'", body.rstrip("\n")]
    return "\n".join(lines) + "\n"


def outputs(parts: list[tuple[str, str, str]], printed: str) -> list[tuple[int, str, list]]:
    """(block number, its expected text, the lines its commands printed) for each output
    block, paired with the commands block before it."""
    got: dict[int, list[str]] = {}
    current = None
    for line in printed.splitlines():
        match = re.fullmatch(r"@@tutorial-block-(\d+)@@", line)
        if match:
            current = int(match.group(1))
            got[current] = []
        elif current is not None:
            got[current].append(line)
    pairs, last_sh = [], None
    for k, (kind, name, body) in enumerate(parts):
        if kind == "sh":
            last_sh = k
        elif kind == "text" and not name:
            assert last_sh is not None, f"output block {k} follows no commands"
            pairs.append((last_sh, body, got.get(last_sh, [])))
    return pairs


def _line_pattern(line: str) -> re.Pattern:
    return re.compile("^" + ".*".join(map(re.escape, line.split("..."))) + "$")


def agrees(expected: str, printed: list[str]) -> bool:
    """Whether `printed` is `expected` line for line (`...` as in the module doc)."""
    want = [line for line in expected.splitlines()]
    while want and not want[-1].strip():
        want.pop()

    def match(i: int, j: int) -> bool:
        if i == len(want):
            return j == len(printed)
        if want[i] == "...":
            return any(match(i + 1, jj) for jj in range(j, len(printed) + 1))
        return j < len(printed) and bool(_line_pattern(want[i]).match(printed[j])) \
            and match(i + 1, j + 1)

    return match(0, 0)


@pytest.mark.parametrize("expected, printed, ok", [
    ("a\nb ... c\n", ["a", "b 12 c"], True),
    ("a\nb ... c\n", ["a", "b 12 c", "d"], False),          # a line more than the text
    ("a\n...\nd\n", ["a", "b", "c", "d"], True),
    ("a\n...\nd\n", ["a", "d"], True),
    ("a\nd\n", ["a", "b", "d"], False),                      # a line left out, not shown
    ("b\na\n", ["a", "b"], False),                           # order counts
])
def test_output_agrees_line_for_line(expected, printed, ok):
    assert agrees(expected, printed) is ok


def test_the_tutorial_runs_as_written(tmp_path):
    parts = blocks(TUTORIAL.read_text())
    assert {k for k, _, _ in parts} == {"tlp", "json", "toml", "sh", "text"}
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "TELEO_RUN_DIR": str(tmp_path / "runs"), "COLUMNS": "160", "PYTHONUNBUFFERED": "1"}
    done = subprocess.run(["bash", "-c", script(parts)], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=900)
    log = (tmp_path / "launch.log").read_text() if (tmp_path / "launch.log").exists() else ""
    assert done.returncode == 0, f"{done.stdout}\n{done.stderr}\n{log}"
    wrong = [f"block {k}: the tutorial says\n{want}\nthe commands printed\n" + "\n".join(got)
             for k, want, got in outputs(parts, done.stdout) if not agrees(want, got)]
    assert wrong == [], "\n\n".join(wrong)
    assert (tmp_path / "cruise.png").stat().st_size > 10_000
