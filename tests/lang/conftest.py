"""Shared fixtures for the language engine tests: paths to the seed tables and test programs."""

from __future__ import annotations

from pathlib import Path

import pytest

from agents.lang import Engine, load_program, parse_percepts

HERE = Path(__file__).parent
FIX = HERE / "fixtures"
PROGRAMS = HERE / "programs"
ROOT = HERE.parent.parent


@pytest.fixture(scope="session")
def table3():
    """The percepts of seed 000, Table 3, read verbatim."""
    return parse_percepts((FIX / "table3_percepts.txt").read_text(), "table3_percepts.txt")


@pytest.fixture(scope="session")
def blocks():
    """The Blocks World with the nonprimitive skills written by hand (the program before the
    problem solver learned them), for the executive's tests; no problem solver."""
    return Engine(load_program(FIX / "blocks_handwritten.tlp"), solver=None)


@pytest.fixture(scope="session")
def minidrive():
    """The executive alone (no problem solver): an impasse stays an impasse."""
    return Engine(load_program(PROGRAMS / "minidrive.tlp"), solver=None)


@pytest.fixture(scope="session")
def minidrive_res():
    return Engine(load_program(PROGRAMS / "minidrive_resources.tlp"))


def me(speed=15.0, limit=25, heading=0.0, position=0):
    """The ego car as a neutral percept list."""
    return ["self", "ME", "speed", speed, "limit", limit, "heading", heading, "position", position]


BLOCKS = ROOT / "programs" / "blocks.tlp"


def figure3_program():
    """programs/blocks.tlp with seed 000's Figure 3 problem, (clear A), as its goal p1 (the
    program itself has no standing goal: a Blocks World problem is a user's goal)."""
    from agents.lang import load_program_text

    return load_program_text(BLOCKS.read_text() + "\n(goals\n  (clear A))\n", str(BLOCKS))
