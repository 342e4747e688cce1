"""What an agent perceives of the bins world: a pure function of a snapshot dict (no state,
no clock), so the agent's perception process needs nothing but the snapshot.

  (robot R1 holding B2 x 3.1 y 0.5)              its own robot; holding none when empty
  (ball B1 colour red bin none dist 2.35 x 1.2 y 1.8)   every ball; bin: the bin it fell into
  (bin red-bin colour red dist 4.1 x 1.5 y 4.2)  every bin
Distances [m] are from the agent's robot, centre to centre (0 for the ball it holds).
"""

from __future__ import annotations

import math
from typing import Any

from teleo_world_bins.world import bin_id
from world.base import r3
from world.errors import WorldError


def perceive(snapshot: dict[str, Any], agent: str) -> list[list[Any]]:
    """The agent's percepts (bins.tlp's form) from a snapshot dict (WorldError naming what is
    missing from a malformed one)."""
    try:
        me = next(r for r in snapshot["robots"] if r["agent"] == agent)
        x, y = me["x"], me["y"]
        out: list[list[Any]] = [["robot", me["id"], "holding", me["holding"] or "none",
                                 "x", r3(x), "y", r3(y)]]
        for b in snapshot["balls"]:
            held = b["id"] == me["holding"]
            out.append(["ball", b["id"], "colour", b["colour"], "bin", b["bin"] or "none",
                        "dist", 0.0 if held else r3(math.hypot(b["x"] - x, b["y"] - y)),
                        "x", r3(b["x"]), "y", r3(b["y"])])
        for colour, (bx, by) in sorted(snapshot["bins"].items()):
            out.append(["bin", bin_id(colour), "colour", colour,
                        "dist", r3(math.hypot(bx - x, by - y)), "x", r3(bx), "y", r3(by)])
    except StopIteration:
        raise WorldError(f"bins snapshot: no robot of agent {agent!r}") from None
    except (KeyError, TypeError, ValueError) as exc:
        raise WorldError(f"bins snapshot: malformed ({exc!r})") from None
    return out
