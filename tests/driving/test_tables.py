"""Seed 000, Tables 7 and 8, on teleo's driving programs: the programs of programs/tables/ are
what the transformations make of programs/driving.tlp; replacing a law changes no skill in the
prioritized notation and every skill in the original one; both notations drive alike."""

from __future__ import annotations

import dataclasses

import pytest

from agents.lang.reading.printer import clause_text
from tests.driving.scenarios import goal, scenario
from tools import law_programs as lp
from tools.commands.simulate import simulate

VARIANTS = {v.name: v for v in lp.variants()}
LAWS = {lp.PEDESTRIANS, lp.SPEED, lp.FAST[0], lp.GIVING_WAY[0]}


def driving_skills(name: str) -> list[str]:
    """The skill clauses of a variant that are not a law's own, as text."""
    return [clause_text(s) for s in VARIANTS[name].program.skills if s.head.pred not in LAWS]


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_the_program_files_are_up_to_date(name):
    v = VARIANTS[name]
    assert v.path.read_text(encoding="utf-8") == lp.text(v), \
        f"{v.path} is stale: run .venv/bin/python bench/driving/tables.py --write"


def test_laws_cost_one_skill_each_in_the_prioritized_notation_and_a_copy_of_all_in_the_other():
    base = len(driving_skills("prioritized_0laws"))
    own = {k: len(VARIANTS[f"prioritized_{k}"].program.skills) - base for k in ("1law", "2laws")}
    assert base >= 20 and own == {"1law": 3, "2laws": 4}         # seed 000: 54; 3 and 1 more
    assert len(VARIANTS["original_1law"].program.skills) == 2 * base + own["1law"]
    assert len(VARIANTS["original_2laws"].program.skills) == 3 * base + own["2laws"]


@pytest.mark.parametrize("replaced", ["fast", "fast_giving_way"])
def test_replacing_laws_changes_no_skill_in_the_prioritized_notation(replaced):
    """seed 000, Table 8: only the goal list and the laws' own skills change."""
    before = VARIANTS["prioritized_2laws"].program
    after = VARIANTS[f"prioritized_{replaced}"].program
    assert driving_skills(f"prioritized_{replaced}") == driving_skills("prioritized_2laws")
    assert [g.literal for g in after.goals] != [g.literal for g in before.goals]
    # in the original notation every driving skill's main clause and a twin per law change
    old = set(driving_skills("original_2laws"))
    changed = [c for c in driving_skills(f"original_{replaced}") if c not in old]
    base = len(driving_skills("prioritized_2laws"))
    assert len(changed) == base * (2 if replaced == "fast" else 3)


def run(name: str, sc):
    """A simulated run of ``sc`` in which every car runs the variant ``name``."""
    program = VARIANTS[name].path
    return simulate(dataclasses.replace(sc, agents=tuple(
        dataclasses.replace(a, program=program) for a in sc.agents)))


@pytest.mark.parametrize("seed", [1, 2, 3, 4, 5])
@pytest.mark.parametrize("laws", ["1law", "2laws"])
def test_both_notations_give_the_same_trace(laws, seed):
    """Pedestrians, traffic, and a walker stepping out in front of the car (the pedestrian law
    pre-empts the errand) while it drives round a right turn: cycle for cycle the same trace
    lines, which hold the actions, the law counters and the world's digest (world/trace.py)."""
    walker = {"at_cycle": 60, "kind": "pedestrian", "ahead_of": "ME", "dist": 12.0,
              "lateral": -1.0, "speed": 1.4}
    sc = scenario(packages=[{"id": "P1", "address": 6, "street": "SECOND"}],
                  goals=[goal("(package-delivered P1)")], events=[walker],
                  pedestrians=20, traffic=2, cycles=300, seed=seed)
    prioritized = run(f"prioritized_{laws}", sc)
    actions = [r["ME"]["actions"] for r in prioritized.records]
    assert actions[0] == [["*gas", 6.25]]                      # the speed law's Table 1 skill
    law_brakes = sum(1 for acts in actions if acts == [["*brake", 100]])
    assert (law_brakes > 0) == (laws == "2laws")               # the pedestrian law's skill
    original = run(f"original_{laws}", sc)
    assert len(prioritized.trace) == len(original.trace) == 300
    first = next((i for i, (a, b) in enumerate(zip(prioritized.trace, original.trace,
                                                                  strict=True))
                  if a != b), None)
    assert first is None, f"seed {seed}: traces differ from cycle {first}"
