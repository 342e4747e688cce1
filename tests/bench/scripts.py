"""Running a bench script as its user does: a real subprocess of this Python in the project's
root, its output captured (the tests of bench/ read its lines and exit status)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def run_script(script: Path, *args: str, timeout: float = 240) -> subprocess.CompletedProcess:
    """``python script args...`` from the project's root, its stdout and stderr as text."""
    return subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True,
                          timeout=timeout, cwd=ROOT)
