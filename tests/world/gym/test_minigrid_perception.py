"""MiniGrid's perception on a known layout (DoorKey-5x5, seed 0), the mission mapping, and
the path affordances."""

from __future__ import annotations

import doctest

import pytest

import world.gym.families.minigrid as mg
from world.domain import get_domain
from world.gym.paths import Cell, Grid, Search

GYM = get_domain("gymnasium")


def _percepts(env: str, seed: int) -> dict[str, list]:
    world = GYM.create({"env": env}, seed, ["ME"])
    return {p[1]: p for p in GYM.perceive(world.snapshot_dict(), "ME")}, world


def _attrs(p: list) -> dict:
    return dict(zip(p[2::2], p[3::2], strict=True))


def test_doorkey_5x5_seed_0_as_laid_out():
    seen, world = _percepts("MiniGrid-DoorKey-5x5-v0", 0)
    state = world.snapshot_dict()["state"]
    me = _attrs(seen["ME"])
    assert (me["x"], me["y"], me["dir"]) == (state["agent"]["x"], state["agent"]["y"],
                                             state["agent"]["dir"])
    assert me["carrying"] == "none"
    assert _attrs(seen["M"])["kind"] == "goal"
    key, door, goal = (_attrs(seen[n]) for n in ("KEY1", "DOOR1", "GOAL1"))
    assert key["type"] == "key" and door["type"] == "door" and door["state"] == "locked"
    assert key["color"] == door["color"] and goal["color"] == "green"
    assert key["via"] == "none" and key["dist"] >= 1 and key["next"] in ("left", "right",
                                                                          "forward", "here")
    assert goal["via"] in ("DOOR1", "KEY1") and goal["free"] == "no"
    for name, o in (("KEY1", key), ("DOOR1", door), ("GOAL1", goal)):
        found = [x for x in state["objects"] if x["name"] == name][0]
        assert (o["x"], o["y"]) == (found["x"], found["y"])


def test_the_next_step_of_a_shortest_path_in_a_corridor():
    # a corridor along y = 1 from x = 1 to x = 5, walls around; the agent at x=1 facing north
    cells = {(x, y): Cell("wall") for x in range(7) for y in (0, 2)}
    cells.update({(0, 1): Cell("wall"), (6, 1): Cell("wall"), (4, 1): Cell("door-closed", "red",
                                                                           "DOOR1")})
    grid = Grid(7, 3, cells)
    search = Search(grid, (1, 1, 3))
    reach = search.to_stand_on(5, 1)
    assert (reach.next, reach.steps, reach.via) == ("right", 6, "")  # turn, 2, toggle+1, 1
    locked = Grid(7, 3, {**cells, (4, 1): Cell("door-locked", "red", "DOOR1")})
    assert Search(locked, (1, 1, 0)).to_stand_on(5, 1).via == "DOOR1"
    assert Search(locked, (1, 1, 0), "red").to_stand_on(5, 1).via == ""
    lava = Grid(7, 3, {**cells, (4, 1): Cell("lava")})
    assert Search(lava, (1, 1, 0)).to_stand_on(5, 1) is None


@pytest.mark.parametrize("text, kind, typ, color", [
    ("use the key to open the door and then get to the goal", "goal", "goal", "any"),
    ("avoid the lava and get to the green goal square", "goal", "goal", "any"),
    ("pick up the purple box", "pickup", "box", "purple"),
    ("go fetch a grey key", "pickup", "key", "grey"),
    ("open the door", "open", "door", "any"),
    ("go to the red door", "goto", "door", "red"),
    ("put the blue ball near the red key", "putnear", "ball", "blue"),
    # BabyAI's phrasings (minigrid.envs.babyai): "a", "next to", "object", "then open"
    ("go to a grey door", "goto", "door", "grey"),
    ("open a door in front of you", "open", "door", "any"),
    ("pick up the green object", "pickup", "object", "green"),
    ("put a grey key next to the red box", "putnext", "key", "grey"),
    ("open the purple door, then open the red door", "open", "door", "purple"),
    ("", "unknown", "none", "any"),
])
def test_the_mission_mapping(text, kind, typ, color):
    got = mg.mission(text)
    assert (got["kind"], got["type"], got["color"]) == (kind, typ, color)


def test_docstring_examples():
    result = doctest.testmod(mg)
    assert result.attempted > 0 and result.failed == 0
