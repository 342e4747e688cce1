"""World benchmark: simulation steps per second with 1, 10 and 50 vehicles (one agent car plus
traffic) and 50 pedestrians in the default city; also perception and rendering cost.

    .venv/bin/python bench/speed/world.py [--steps N]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

# this file is bench/speed/world.py: keep its folder off the path so `world` means the package
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != Path(__file__).parent.resolve()]

from world.driving.config import WorldConfig  # noqa: E402
from world.driving.perception import perceive  # noqa: E402
from world.driving.render import render_png  # noqa: E402
from world.driving.simulation import Simulation  # noqa: E402


def steps_per_second(vehicles: int, pedestrians: int, steps: int) -> tuple[float, float]:
    sim = Simulation(WorldConfig(pedestrians=pedestrians, traffic=vehicles - 1), seed=1,
                     agents=["ME"])
    sim.apply_actions("ME", [["*gas", 25], ["*steer", 2]])
    t0 = time.perf_counter()
    for _ in range(steps):
        sim.step()
    stepping = steps / (time.perf_counter() - t0)
    snap = sim.snapshot()
    t0 = time.perf_counter()
    for _ in range(200):
        perceive(snap, "ME")
    return stepping, (time.perf_counter() - t0) / 200 * 1e3


def _positive(text: str) -> int:
    """A count of steps >= 1, else a usage error."""
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"expected a count of steps >= 1, got {text!r}")
    return int(text)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--steps", type=_positive, default=2000)
    args = parser.parse_args()
    print(f"world bench: default city (4 x 4 streets, 100 m blocks), dt 0.1 s, {args.steps} steps")
    print(f"{'vehicles':>9} {'pedestrians':>12} {'steps/s':>10} {'x realtime':>11} "
          f"{'perceive ms':>12}")
    for vehicles in (1, 10, 50):
        sps, perceive_ms = steps_per_second(vehicles, 50, args.steps)
        print(f"{vehicles:>9} {50:>12} {sps:>10.0f} {sps * 0.1:>11.0f} {perceive_ms:>12.3f}")
    sim = Simulation(WorldConfig(pedestrians=50, traffic=9), seed=1, agents=["ME"])
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        for _ in range(5):
            render_png(sim.snapshot(), Path(tmp) / "frame.png")
        print(f"render_png: {(time.perf_counter() - t0) / 5 * 1e3:.1f} ms per frame")


if __name__ == "__main__":
    main()
