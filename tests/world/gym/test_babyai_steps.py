"""A compound BabyAI mission is pursued one action at a time (world/gym/families/instructions.py):
the step the agent is on is the first action, in the order the mission asks for them, that the
environment's own verifier has not marked done; "A after you B" asks for B first."""

from __future__ import annotations

import warnings
from pathlib import Path

from minigrid.envs.babyai.core.verifier import (
    AfterInstr,
    AndInstr,
    BeforeInstr,
    GoToInstr,
    ObjDesc,
    OpenInstr,
    PickupInstr,
    PutNextInstr,
)

from tools.commands.simulate import simulate
from world.gym.families.instructions import _steps, _words
from world.gym.families.minigrid import mission
from world.run_scenario import load_scenario

DOORKEY = Path(__file__).resolve().parents[3] / "scenarios" / "minigrid_doorkey.toml"


def order(instr) -> list[tuple[str, bool]]:
    return [(_words(leaf), done) for leaf, done in _steps(instr, False)]


def test_after_asks_for_its_second_part_first_and_done_parts_are_passed() -> None:
    instr = AfterInstr(GoToInstr(ObjDesc("key")),
                       AndInstr(OpenInstr(ObjDesc("door", "red")),
                                PutNextInstr(ObjDesc("ball"), ObjDesc(None, "green"))))
    assert order(instr) == [("open a red door", False),
                            ("put a ball next to a green object", False),
                            ("go to a key", False)]
    instr.instr_b.a_done = "success"           # the door opened: the put is next
    assert [done for _, done in order(instr)] == [True, False, False]
    instr.b_done = "success"                   # the whole "and" done: then the key
    assert order(instr)[-1] == ("go to a key", False) and \
        [done for _, done in order(instr)] == [True, True, False]


def test_each_step_reads_as_a_mission() -> None:
    instr = BeforeInstr(PickupInstr(ObjDesc(None, "grey")), GoToInstr(ObjDesc("door")))
    kinds = [mission(words) for words, _ in order(instr)]
    assert [(m["kind"], m["type"], m["color"]) for m in kinds] == \
        [("pickup", "object", "grey"), ("goto", "door", "any")]


def test_a_sequence_mission_is_won_step_by_step() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # BabyAI's own deprecation warnings
        run = simulate(load_scenario(DOORKEY, ["world.env=BabyAI-GoToSeq-v0"]), cycles=700,
                       seed=0, keep_every=1)
    assert run.final["state"]["mission"] == ("go to a key and go to a grey door after you go to "
                                             "a yellow key and go to the green box")
    assert list(dict.fromkeys(s["state"]["step"] for s in run.snapshots)) == [
        "go to a yellow key", "go to a green box", "go to a key", "go to a grey door", ""]
    episode = run.final["episode"]
    assert episode["terminated"] and episode["reward"] > 0, episode


def test_two_puts_one_after_the_other() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        run = simulate(load_scenario(DOORKEY, ["world.env=BabyAI-MoveTwoAcrossS5N2-v0"]),
                       cycles=700, seed=1)
    episode = run.final["episode"]
    assert episode["terminated"] and episode["reward"] > 0, episode
