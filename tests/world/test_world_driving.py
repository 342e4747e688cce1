"""The percepts are drivable: a small reactive controller that reads only `perceive` output
(lane lines, self, package guidance) keeps its lane, turns where the navigation says, and
delivers a package. It is the shape of the teleoreactive driving program, written in Python."""

from __future__ import annotations

from world.driving.config import load_world_config
from world.driving.perception import perceive
from world.driving.simulation import Simulation


def attrs(percepts: list[list], kind: str) -> list[dict]:
    return [dict(zip(p[2::2], p[3::2], strict=True)) | {"id": p[1]}
            for p in percepts if p[0] == kind]


def controller(percepts: list[list]) -> list[list]:
    """Percepts in, Table 4 actions out."""
    (me,) = attrs(percepts, "self")
    yellow = next(x for x in attrs(percepts, "lane-line") if x["color"] == "YELLOW")
    package = next((p for p in attrs(percepts, "package") if p["delivered"] == "NIL"), None)
    if package is None:
        return [["*brake", 100]]
    turn, dist = package["next-turn"], package["turn-dist"]
    target = 8.0
    steer = 1.0 * yellow["angle"] - 3.0 * (yellow["dist"] + 2.0)   # keep 2 m right of yellow
    if turn == "LEFT" and dist <= 8.0:
        steer, target = 15.1, 5.0      # radius 10 m: from the right lane to the far right lane
    elif turn == "RIGHT" and dist <= 8.0:
        steer, target = -24.0, 5.0     # radius 6 m into the near right lane
    elif turn in ("LEFT", "RIGHT") and dist < 30.0:
        target = 5.0
    if turn == "ARRIVING":
        target = 0.0 if dist < 1.0 else min(target, 2.0 + dist / 3.0)
    pedal = (["*gas", 40] if me["speed"] < target - 0.3
             else ["*brake", 100 if target == 0.0 else 30] if me["speed"] > target + 0.3
             else ["*cruise"])
    return [pedal, ["*steer", max(-40.0, min(40.0, steer))]]


def run(address: int, street: str, seconds: float,
        start: str = "FIRST") -> tuple[Simulation, list]:
    config = load_world_config({
        "pedestrians": 0, "traffic": 0,
        "packages": [{"id": "P1", "address": address, "street": street, "owner": "ME"}],
        "cars": [{"agent": "ME", "street": start, "from": "A", "toward": "B", "along": 20}]})
    sim = Simulation(config, seed=1, agents=["ME"])
    turns = []
    for _ in range(round(seconds / config.dt)):
        percepts = perceive(sim.snapshot(), "ME")
        turns += [p["next-turn"] for p in attrs(percepts, "package")][:1]
        sim.apply_actions("ME", controller(percepts))
        sim.step()
        if sim.snapshot().counters["ME"]["deliveries"]:
            break
    return sim, turns


def test_one_left_turn_then_delivery_without_breaking_a_law() -> None:
    sim, turns = run(4, "B", 60.0)        # B 4: east side of B, first block north of FIRST
    counters = sim.snapshot().counters["ME"]
    assert counters["deliveries"] == 1
    assert turns[0] == "LEFT" and turns[-1] == "ARRIVING"
    assert counters["off_road"] == counters["yellow_crossings"] == 0
    assert counters["speeding_cycles"] == 0


def test_a_loop_around_the_block_to_reach_the_west_side() -> None:
    sim, turns = run(3, "B", 120.0)       # B 3: west side, reached southbound: a loop
    counters = sim.snapshot().counters["ME"]
    assert counters["deliveries"] == 1 and turns[0] == "STRAIGHT" and "LEFT" in turns
    assert counters["off_road"] == counters["yellow_crossings"] == 0


def test_a_right_turn_then_delivery() -> None:
    sim, turns = run(1, "B", 60.0, start="SECOND")    # B 1: west side, southbound from SECOND
    counters = sim.snapshot().counters["ME"]
    assert counters["deliveries"] == 1 and turns[0] == "RIGHT" and turns[-1] == "ARRIVING"
    assert counters["off_road"] == counters["yellow_crossings"] == 0
