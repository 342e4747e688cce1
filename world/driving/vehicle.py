"""The agent car's controls and vehicle model, and the seed's driving actions (seed 000, Table 4).

Vehicle model: a kinematic bicycle whose reference point is the body centre (slip neglected).
Each step of dt [s]:
    a = MAX_ACCEL * throttle/100 - MAX_BRAKE * brake/100 - DRAG * v^2 - ROLLING   (while v > 0)
    v <- max(0, v + a * dt)                                  (no reverse gear)
    yaw rate = v / WHEELBASE * tan(wheel angle)              [rad/s], wheel angle + = left
The resulting velocity and yaw rate are set on the car's pymunk body, which pymunk integrates.
At full throttle the speed settles near sqrt((MAX_ACCEL - ROLLING) / DRAG) ~ 24.7 m/s;
at throttle p% it settles near sqrt((3 p/100 - 0.05) / 0.0048) m/s (e.g. 30% -> 13.5 m/s).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from world.driving import ACTIONS

MAX_ACCEL = 3.0       # [m/s^2] at throttle 100
MAX_BRAKE = 8.0       # [m/s^2] at brake 100
DRAG = 0.0048         # [1/m] quadratic drag coefficient
ROLLING = 0.05        # [m/s^2] rolling resistance while moving
WHEELBASE = 2.7       # [m]
MAX_WHEEL = 40.0      # [deg] steering limit
CAR_LENGTH, CAR_WIDTH = 4.5, 1.8   # [m]


@dataclass
class Controls:
    """Persistent pedal and wheel settings of one agent car."""

    throttle: float = 0.0     # [%] 0..100
    brake: float = 0.0        # [%] 0..100
    wheel: float = 0.0        # [deg] -40..40, + = left


def accelerate(v: float, c: Controls, dt: float) -> float:
    """New speed [m/s] after dt [s] under the controls."""
    a = MAX_ACCEL * c.throttle / 100.0
    if v > 0.0:
        a -= MAX_BRAKE * c.brake / 100.0 + DRAG * v * v + ROLLING
    return max(0.0, v + a * dt)


def yaw_rate(v: float, wheel_deg: float) -> float:
    """Kinematic bicycle yaw rate [rad/s] at speed v [m/s] and wheel angle [deg]."""
    return v / WHEELBASE * math.tan(math.radians(wheel_deg))


def _outcome(action: Any, reason: str = "") -> dict[str, Any]:
    return {"action": list(action) if isinstance(action, list | tuple) else [repr(action)],
            "status": "failed" if reason else "done", "reason": reason}


def _number_arg(action: list, lo: float, hi: float) -> tuple[float | None, str]:
    name = action[0]
    if len(action) != 2:
        return None, f"({name} value) takes 1 argument, got {len(action) - 1}"
    value = action[1]
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        return None, f"{name}: expected a number in [{lo:g}, {hi:g}], got {value!r}"
    if not lo <= value <= hi:
        return None, f"{name}: {value:g} out of range [{lo:g}, {hi:g}]"
    return float(value), ""


def apply_action(c: Controls, action: Any) -> dict[str, Any]:
    """Apply one neutral-form action to the controls; return its outcome dict. Never raises."""
    if not isinstance(action, list | tuple) or not action or not isinstance(action[0], str):
        return _outcome(action, f"malformed action {action!r}: expected [name, args...]")
    action = list(action)
    name = action[0]
    if name in ("*cruise", "*straighten"):
        if len(action) != 1:
            return _outcome(action, f"({name}) takes no arguments, got {len(action) - 1}")
        if name == "*straighten":
            c.wheel = 0.0
        return _outcome(action)
    limits = {"*gas": (0.0, 100.0), "*brake": (0.0, 100.0), "*steer": (-MAX_WHEEL, MAX_WHEEL)}
    if name not in limits:
        return _outcome(action, f"unknown action {name!r}; known: {' '.join(ACTIONS)}")
    value, reason = _number_arg(action, *limits[name])
    if value is None:
        return _outcome(action, reason)
    if name == "*gas":
        c.throttle, c.brake = value, 0.0
    elif name == "*brake":
        c.brake, c.throttle = value, 0.0
    else:
        c.wheel = value
    return _outcome(action)
