"""docs/tutorial.md runs as written (issue 12, item 15): its files are written, its commands
run in order in one shell in an empty folder, and every line of its expected outputs appears
in what they printed (`...` stands for what changes from run to run)."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TUTORIAL = ROOT / "docs" / "tutorial.md"
FENCE = re.compile(r"^```([^\n]*)\n(.*?)^```$", re.M | re.S)


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
    lines = ["set -e"]
    for kind, name, body in parts:
        if name:
            lines += [f"cat > {name} <<'TUTORIAL_EOF'", body.rstrip("\n"), "TUTORIAL_EOF"]
        elif kind == "sh":
            lines.append(body.rstrip("\n"))
    return "\n".join(lines) + "\n"


def expected(parts: list[tuple[str, str, str]]) -> list[str]:
    return [line for kind, name, body in parts if kind == "text" and not name
            for line in body.splitlines() if line.strip()]


def matches(line: str, output: list[str]) -> bool:
    pattern = re.compile("^" + ".*".join(map(re.escape, line.split("..."))) + "$")
    return any(pattern.match(got) for got in output)


def test_the_tutorial_runs_as_written(tmp_path):
    parts = blocks(TUTORIAL.read_text())
    assert {k for k, _, _ in parts} == {"tlp", "json", "toml", "sh", "text"}
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}",
           "TELEO_RUN_DIR": str(tmp_path / "runs"), "COLUMNS": "160"}
    done = subprocess.run(["bash", "-c", script(parts)], cwd=tmp_path, env=env,
                          capture_output=True, text=True, timeout=600)
    output = (done.stdout + done.stderr).splitlines()
    log = (tmp_path / "launch.log").read_text() if (tmp_path / "launch.log").exists() else ""
    assert done.returncode == 0, f"{done.stdout}\n{done.stderr}\n{log}"
    missing = [line for line in expected(parts) if not matches(line, output)]
    assert missing == [], "\n".join(output)
    assert (tmp_path / "cruise.png").stat().st_size > 10_000
