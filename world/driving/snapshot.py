"""The observable world state of one cycle, as frozen dataclasses with an exact plain-data round
trip (`to_dict` / `from_dict`: str/int/float/bool/list/dict only, msgpack-able).

Units: positions [m] in the city frame (x east, y north), headings [deg] (0 = east,
counter-clockwise positive, in (-180, 180]), speeds [m/s], wheel angle [deg] (+ = left),
pedals [%], time [s].
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from functools import cache
from typing import Any

from world.driving.config import WorldConfig, load_world_config
from world.errors import WorldError
from world.parsed import parsed_by_value

COUNTERS = ("pedestrian_hits", "vehicle_collisions", "off_road", "yellow_crossings",
            "speeding_cycles", "deliveries")


_config = parsed_by_value(load_world_config)  # every snapshot of a run carries the same config

@dataclass(frozen=True)
class CarState:
    """A vehicle: kind "agent" (driven by an agent through actions) or "traffic"."""

    id: str
    kind: str
    x: float
    y: float
    heading: float
    speed: float
    wheel: float = 0.0
    throttle: float = 0.0
    brake: float = 0.0


@dataclass(frozen=True)
class PedState:
    """A pedestrian; mode "walk" (sidewalk), "cross" (crossing the road), "stand", or "down"
    (hit by a car: stays where it fell)."""

    id: str
    x: float
    y: float
    heading: float
    speed: float
    mode: str


@dataclass(frozen=True)
class PackageState:
    id: str
    address: int
    street: str
    owner: str
    delivered: bool = False


@dataclass(frozen=True)
class WorldSnapshot:
    cycle: int
    time: float
    config: WorldConfig
    cars: tuple[CarState, ...] = ()
    pedestrians: tuple[PedState, ...] = ()
    packages: tuple[PackageState, ...] = ()
    counters: dict[str, dict[str, int]] = field(default_factory=dict)
    events: tuple[dict[str, Any], ...] = ()     # what happened during the step into this cycle
    blocked: tuple[str, ...] = ()               # segment ids closed by injected events

    def car(self, car_id: str) -> CarState:
        for c in self.cars:
            if c.id == car_id:
                return c
        raise WorldError(f"snapshot of cycle {self.cycle}: no car {car_id!r}; "
                         f"cars: {[c.id for c in self.cars]}")

    def to_dict(self) -> dict[str, Any]:
        return {
            "domain": "driving", "cycle": self.cycle, "time": self.time,
            "config": self.config.to_dict(),
            "cars": [dict(vars(c)) for c in self.cars],  # flat records of atoms: a copy is
            "pedestrians": [dict(vars(p)) for p in self.pedestrians],  # asdict, 10x faster
            "packages": [dict(vars(p)) for p in self.packages],
            "counters": {a: dict(c) for a, c in self.counters.items()},
            "events": [dict(e) for e in self.events],
            "blocked": list(self.blocked),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> WorldSnapshot:
        """Rebuild a snapshot from `to_dict` output; raise WorldError naming what is wrong."""
        try:
            return cls(
                cycle=int(d["cycle"]), time=d["time"], config=_config(d["config"]),
                cars=tuple(_record(CarState, c) for c in d["cars"]),
                pedestrians=tuple(_record(PedState, p) for p in d["pedestrians"]),
                packages=tuple(_record(PackageState, p) for p in d["packages"]),
                counters={a: dict(c) for a, c in d["counters"].items()},
                events=tuple(dict(e) for e in d["events"]),
                blocked=tuple(d["blocked"]),
            )
        except (KeyError, TypeError, AttributeError) as exc:
            raise WorldError(f"WorldSnapshot.from_dict: malformed snapshot dict ({exc!r})") from exc


@cache
def _names(kind: type) -> frozenset[str]:
    return frozenset(f.name for f in fields(kind))


def _record(kind: type, d: dict[str, Any]) -> Any:
    names = _names(kind)
    if not names.issuperset(d):
        raise WorldError(f"{kind.__name__}: unknown keys {sorted(set(d) - names)}")
    return kind(**d)
