"""A bounded subset of the fuzz drill (bench/faults/fuzz.py): a few hundred inputs per reader with a
fixed seed, the drill's minimal cases first; none may raise anything but the reader's own
error (fault drill 4, F7 and F9)."""

from __future__ import annotations

import importlib.util
import sys
import tempfile
from pathlib import Path

import pytest

from .conftest import ROOT


def load_fuzz():
    spec = importlib.util.spec_from_file_location("fuzz_drill",
                                                  ROOT / "bench" / "faults" / "fuzz.py")
    module = sys.modules["fuzz_drill"] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


fuzz = load_fuzz()
READERS = {"program": fuzz.program_reader, "percepts": fuzz.percept_reader,
           "goal": fuzz.goal_reader, "event": fuzz.event_reader,
           "scenario": lambda: fuzz.scenario_reader(TMP)}
TMP = Path(tempfile.mkdtemp(prefix="teleo-fuzz-"))


@pytest.mark.parametrize("name", sorted(READERS))
def test_fuzzed_inputs_are_accepted_or_refused_never_a_crash(name):
    reader = READERS[name]()
    tally = fuzz.fuzz(name, reader, 400, seed=11)
    assert tally.crashes == [], tally.crashes[0][1]
    assert tally.inputs == 400
    assert tally.accepted > 0 and tally.refused > 0  # both paths were exercised


@pytest.mark.parametrize("name", sorted(READERS))
def test_the_drills_minimal_cases_are_refused(name):
    reader = READERS[name]()
    tally = fuzz.fuzz(name, reader, len(reader.minimal), seed=0)
    assert tally.crashes == [] and tally.accepted == 0
