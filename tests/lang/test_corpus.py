"""Corpus: small programs with the beliefs and actions they must produce (tests/lang/corpus/*)."""

from __future__ import annotations

import json

import pytest

from agents.lang import Engine, load_program, parse_percepts

from .conftest import HERE

CASES = sorted(p.name for p in (HERE / "corpus").iterdir() if p.is_dir())


@pytest.mark.parametrize("case", CASES)
def test_corpus_case(case):
    folder = HERE / "corpus" / case
    engine = Engine(load_program(folder / "program.tlp"))
    percepts = parse_percepts((folder / "percepts.txt").read_text(), "percepts.txt")
    result = engine.cycle(engine.initial_state(), percepts)
    beliefs = sorted(str(b) for b in result.beliefs)
    assert beliefs == sorted((folder / "beliefs.txt").read_text().split("\n")[:-1])
    expected = [json.loads(line) for line in (folder / "actions.txt").read_text().splitlines()]
    assert [a.to_list() for a in result.decision.actions] == expected


def test_corpus_is_not_empty():
    assert {"rooms", "speed", "tower"} <= set(CASES)
