"""Comments and docstrings state what must stay true and why, not history: no issue numbers,
drill or trial names, dates or measured figures in the code of agents/, bus/, world/ and tools/
(the figures live in docs/benchmarks.md, the drills in docs/faults.md), and no reference to a
design file outside the repository."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("agents", "bus", "world", "tools")
HISTORY = {
    "an issue number": re.compile(r"\b[Ii]ssues? #?\d+"),
    "a drill or trial name": re.compile(r"\b(?:drills?|trial) [A-Za-z]{0,2}\d"),
    "a date": re.compile(r"\b20\d\d-\d\d-\d\d\b"),
    "a measured figure": re.compile(r"(?:~|about |measured:? )\d+(?:\.\d+)? ?ms\b"),
    "a file outside the repository": re.compile(r"\b(?:shared/)?(?:DESIGN|STYLE)\.md|notes/zenoh"),
}


def comment_lines(path: Path) -> list[tuple[int, str]]:
    """The lines of ``path`` that hold a comment or sit in a docstring (a line inside
    triple quotes), with their numbers."""
    out, inside = [], False
    for n, line in enumerate(path.read_text().splitlines(), 1):
        quotes = line.count('"""')
        if inside or quotes or "#" in line:
            out.append((n, line if inside or quotes else line[line.index("#"):]))
        if quotes % 2:
            inside = not inside
    return out


def test_comments_say_what_holds_not_what_happened() -> None:
    found = [f"{path.relative_to(ROOT)}:{n}: {what}: {line.strip()}"
             for package in PACKAGES for path in sorted((ROOT / package).rglob("*.py"))
             for n, line in comment_lines(path)
             for what, pattern in HISTORY.items() if pattern.search(line)]
    assert found == []


def test_the_check_finds_what_it_looks_for(tmp_path) -> None:
    sample = tmp_path / "m.py"
    sample.write_text('"""Kept apart (issue 31).\n\nSee DESIGN.md."""\n\nX = 1  # drill N1\n'
                      'Y = "issue 2"\n')
    hits = [(n, what) for n, line in comment_lines(sample)
            for what, pattern in HISTORY.items() if pattern.search(line)]
    assert hits == [(1, "an issue number"), (3, "a file outside the repository"),
                    (5, "a drill or trial name")]
