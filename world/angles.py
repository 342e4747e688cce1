"""Angle arithmetic shared by perception and the simulated actors [deg]."""

from __future__ import annotations

import math


def wrap(deg: float) -> float:
    """Angle folded into (-180, 180] [deg]."""
    deg = math.fmod(deg, 360.0)
    if deg > 180.0:
        deg -= 360.0
    elif deg <= -180.0:
        deg += 360.0
    return deg
