"""Small driving scenarios built in code for the driving program's tests."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

from tools.commands.simulate import SimRun
from world.driving.snapshot import WorldSnapshot
from world.run_scenario import Scenario, load_scenario, scenario_from_dict

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = str(ROOT / "programs" / "driving.tlp")
START = {"agent": "ME", "street": "B", "from": "FIRST", "toward": "SECOND", "along": 20.0}


def scenario(*, packages: list[dict[str, Any]], goals: list[dict[str, Any]] | None = None,
             events: list[dict[str, Any]] | None = None, pedestrians: int = 0, traffic: int = 0,
             seed: int = 7, cycles: int = 300, cars: list[dict[str, Any]] | None = None,
             program: str = PROGRAM) -> Scenario:
    """A 4x4 city; by default ME on street B heading north from FIRST, 20 m into the block.
    Every car runs ``program``; a package without an owner is ME's."""
    cars = cars or [START]
    doc = {
        "run": {"name": "test", "cycles": cycles, "seed": seed},
        "world": {"grid": [4, 4], "block_length": 100.0, "speed_limit": 15.0,
                  "pedestrians": pedestrians, "traffic": traffic, "cars": cars,
                  "packages": [{"owner": "ME", **p} for p in packages]},
        "agents": [{"id": c["agent"], "program": program} for c in cars],
        "goals": goals or [],
        "events": events or [],
    }
    return scenario_from_dict(doc, ROOT / "tests" / "driving" / "scenario.toml")


def goal(text: str, at: int = 0, agent: str = "ME", priority: int = 5) -> dict[str, Any]:
    """A scripted user goal, as `teleo goal post` would post it."""
    return {"agent": agent, "goal": text, "priority": priority, "at_cycle": at}


def shipped(name: str) -> Scenario:
    """A scenario of scenarios/ (its program paths resolved from the repository root)."""
    sc = load_scenario(ROOT / "scenarios" / name)
    agents = tuple(dataclasses.replace(a, program=ROOT / a.program) for a in sc.agents)
    return dataclasses.replace(sc, agents=agents)


def final(run: SimRun) -> WorldSnapshot:
    """The last state of a simulated run (its snapshot dict read back)."""
    return WorldSnapshot.from_dict(run.final)
