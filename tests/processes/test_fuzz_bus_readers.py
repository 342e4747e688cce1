"""A bounded subset of the fuzz drill's bus readers (bench/faults/fuzz.py; issue 24, item 4): each
process's reader of each message it takes from the bus, fed a few hundred mutated real
messages (wrong types in every field, deep nesting, huge numbers, NaN, unhashables, cut
bytes): accepted or refused naming a field, never a crash or a hang. The full drill runs
10^5 inputs per reader (docs/faults.md, "Hostile input")."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BUS_READERS = ("actions-driving", "actions-blocks", "actions-office",
               "world-state-driving", "world-state-blocks", "world-state-office",
               "percepts-msg", "executive", "executive-blocks", "executive-office", "memory",
               "intention", "codec")


def load_fuzz():
    spec = importlib.util.spec_from_file_location("fuzz_drill",
                                                  ROOT / "bench" / "faults" / "fuzz.py")
    module = sys.modules["fuzz_drill"] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def readers(tmp_path_factory):
    fuzz = load_fuzz()
    return fuzz, fuzz.make_readers(tmp_path_factory.mktemp("fuzz"))


@pytest.mark.parametrize("name", BUS_READERS)
def test_a_process_reading_fuzzed_messages_accepts_or_refuses_naming_the_field(readers, name):
    fuzz, made = readers
    tally = fuzz.fuzz(name, made[name](), 300, seed=24, limit_s=10.0)
    assert tally.crashes == [], tally.crashes[0][1]
    assert tally.hangs == [] and tally.unnamed == [], (tally.hangs[:3], tally.unnamed[:3])
    assert tally.inputs == 300 and tally.accepted > 0 and tally.refused > 0


def test_the_drill_lists_every_reader_it_has(readers):
    fuzz, made = readers
    assert set(fuzz.READERS) == set(made)
