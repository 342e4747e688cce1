"""programs/minigrid.tlp, the one program, solves a handful of seeds of several MiniGrid
tasks through `teleo simulate`'s cycle (in-process), never stepping into lava or touching a
moving obstacle; `teleo explain` reads its decisions."""

from __future__ import annotations

from pathlib import Path

import pytest

from tools.commands.simulate import simulate
from world.run_scenario import load_scenario

ROOT = Path(__file__).resolve().parents[3]
DOORKEY = ROOT / "scenarios" / "minigrid_doorkey.toml"


@pytest.mark.parametrize("env, seeds", [
    ("MiniGrid-DoorKey-8x8-v0", range(3)),
    ("MiniGrid-KeyCorridorS3R3-v0", (2, 4, 18)),     # a key put down behind a closed door
    ("MiniGrid-UnlockPickup-v0", range(2)),
    ("MiniGrid-LavaCrossingS9N2-v0", range(2)),
    ("MiniGrid-Dynamic-Obstacles-8x8-v0", range(2)),
    ("MiniGrid-GoToDoor-8x8-v0", range(2)),
    ("MiniGrid-ObstructedMaze-1Dlh-v0", (45,)),        # the key's box carried aside first
    ("MiniGrid-RedBlueDoors-8x8-v0", (0,)),            # two doors in order
    ("MiniGrid-ObstructedMaze-Full-v1", (2,)),         # two boxes hold a key for the door
    ("BabyAI-PutNextLocal-v0", (0, 3)),                # next to: beside, not diagonal
    ("BabyAI-PickupDist-v0", (4,)),                    # "the green object"
    ("BabyAI-OpenTwoDoors-v0", (0,)),                  # "..., then open the red door"
])
def test_the_program_wins_the_episode(env, seeds):
    scenario = load_scenario(DOORKEY, [f"world.env={env}"])
    for seed in seeds:
        run = simulate(scenario, cycles=700, seed=seed)
        episode, counters = run.final["episode"], run.final["counters"]["ME"]
        assert episode["terminated"] and episode["reward"] > 0, (env, seed, episode)
        assert counters["lava"] == 0 and counters["collisions"] == 0, (env, seed, counters)
        assert len(run.records) == episode["steps"] + 1          # the run ended with it
        goals = dict(run.records[-1]["ME"]["goals"])
        assert goals["p2"] in ("satisfied", "achieved"), (env, seed, goals)
