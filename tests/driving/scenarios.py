"""Small driving scenarios built in code for the driving program's tests."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from world.run_scenario import Scenario, scenario_from_dict

ROOT = Path(__file__).resolve().parents[2]
PROGRAM = str(ROOT / "programs" / "driving.tlp")


def scenario(*, packages: list[dict[str, Any]], goals: list[dict[str, Any]] | None = None,
             events: list[dict[str, Any]] | None = None, pedestrians: int = 0, traffic: int = 0,
             seed: int = 7, cycles: int = 300) -> Scenario:
    """A 4x4 city with ME on street B heading north from FIRST, 20 m into the block."""
    doc = {
        "run": {"name": "test", "cycles": cycles, "seed": seed},
        "world": {"grid": [4, 4], "block_length": 100.0, "speed_limit": 15.0,
                  "pedestrians": pedestrians, "traffic": traffic,
                  "cars": [{"agent": "ME", "street": "B", "from": "FIRST", "toward": "SECOND",
                            "along": 20.0}],
                  "packages": [{"owner": "ME", **p} for p in packages]},
        "agents": [{"id": "ME", "program": PROGRAM}],
        "goals": goals or [],
        "events": events or [],
    }
    return scenario_from_dict(doc, ROOT / "tests" / "driving" / "scenario.toml")
