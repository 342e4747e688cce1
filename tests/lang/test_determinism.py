"""Decisions and explanations are identical across processes with different string hashing."""

from __future__ import annotations

import os
import subprocess
import sys

from .conftest import ROOT

SCRIPT = """
from agents.lang import Engine, load_program
from tests.lang.test_blocks import percepts
engine = Engine(load_program("tests/lang/fixtures/blocks_handwritten.tlp"))
state = engine.add_goal(engine.initial_state(), "(on A D)", priority=0)
world = percepts({"A": "T", "B": "A", "C": "B", "D": "T", "E": "D"})
result = engine.cycle(state, world)
print(result.decision.explain())
print(sorted(map(str, result.beliefs)))
"""


def under_hash_seeds(script: str) -> list[str]:
    """The output of ``script`` run in three processes with different string hashing."""
    outputs = []
    for seed in ("1", "2", "3"):
        env = {**os.environ, "PYTHONHASHSEED": seed}
        done = subprocess.run([sys.executable, "-c", script], cwd=ROOT, env=env,
                              capture_output=True, text=True, check=True)
        outputs.append(done.stdout)
    return outputs


def test_same_output_under_different_hash_seeds():
    outputs = under_hash_seeds(SCRIPT)
    assert outputs[0] == outputs[1] == outputs[2]
    assert "actions: (*unstack E D)" in outputs[0]
