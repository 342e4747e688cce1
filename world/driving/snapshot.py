"""The observable world state of one cycle, as frozen dataclasses with an exact plain-data round
trip (`to_dict` / `from_dict`: str/int/float/bool/list/dict only, msgpack-able).

Units: positions [m] in the city frame (x east, y north), headings [deg] (0 = east,
counter-clockwise positive, in (-180, 180]), speeds [m/s], wheel angle [deg] (+ = left),
pedals [%], time [s].
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from bus.schema import Bool, Int, ListOf, Num, OneOf, Record, Str
from world.base import COMMON, config_reader, rebuild, record
from world.driving.config import WorldConfig, load_world_config
from world.errors import WorldError

COUNTERS = ("pedestrian_hits", "vehicle_collisions", "off_road", "yellow_crossings",
            "speeding_cycles", "deliveries")


read_config = config_reader(load_world_config)  # every snapshot of a run carries the same config

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
            "pedestrians": [dict(vars(p)) for p in self.pedestrians],  # asdict, far cheaper
            "packages": [dict(vars(p)) for p in self.packages],
            "counters": {a: dict(c) for a, c in self.counters.items()},
            "events": [dict(e) for e in self.events],
            "blocked": list(self.blocked),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> WorldSnapshot:
        """Rebuild a snapshot from `to_dict` output; raise WorldError naming what is wrong
        (the field, checked against SNAPSHOT, or the config's key)."""
        return rebuild(cls, SNAPSHOT, d, lambda: cls(
            cycle=int(d["cycle"]), time=d["time"], config=read_config(d["config"]),
            cars=tuple(record(CarState, c) for c in d["cars"]),
            pedestrians=tuple(record(PedState, p) for p in d["pedestrians"]),
            packages=tuple(record(PackageState, p) for p in d["packages"]),
            counters={a: dict(c) for a, c in d["counters"].items()},
            events=tuple(dict(e) for e in d["events"]),
            blocked=tuple(d["blocked"]),
        ))


MAX_COORD = 1e6    # [m] a position's coordinate, either way (the city is a few km wide)
MAX_RATE = 1e4     # a speed [m/s], angle [deg] or pedal [%], either way
_POS, _RATE = Num(-MAX_COORD, MAX_COORD), Num(-MAX_RATE, MAX_RATE)
SNAPSHOT = Record({
    "cycle": Int(), "time": Num(), "config": Record({}, open=True),
    "cars": ListOf(Record({"id": Str(), "kind": Str(), "x": _POS, "y": _POS,
                           "heading": _RATE, "speed": _RATE},
                          {"wheel": _RATE, "throttle": _RATE, "brake": _RATE}, what="a car")),
    "pedestrians": ListOf(Record({"id": Str(), "x": _POS, "y": _POS, "heading": _RATE,
                                  "speed": _RATE, "mode": Str()}, what="a pedestrian")),
    "packages": ListOf(Record({"id": Str(), "address": Int(), "street": Str(),
                               "owner": Str()}, {"delivered": Bool()}, what="a package")),
    **COMMON, "blocked": ListOf(Str()),
}, {"domain": OneOf(("driving",))}, open=True, what="a driving snapshot")
"""The fields of `WorldSnapshot.to_dict` as perception relies on them (its config, plain data,
is read by load_world_config, which names a bad key, once per distinct config); other
top-level keys are let through (a later version may add some)."""

