"""The observable state of the office world in one cycle, as frozen dataclasses with an exact
plain-data round trip (`to_dict` / `from_dict`: str/int/float/bool/list/dict only).

A robot's `known_*` fields are its navigator's memory (door states, where people were last
seen, obstacles it bumped into): what perception reports, as opposed to the truth in
`doors`, `people` and `obstacles`. Units: [m], [deg] (0 = east, counter-clockwise), [m/s],
[s], [C].
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from bus.schema import (
    AnyOf,
    Atom,
    Int,
    ListOf,
    MapOf,
    Num,
    OneOf,
    Record,
    Str,
    TupleOf,
)
from world.base import COMMON, config_reader, rebuild, record
from world.errors import WorldError
from world.office.config import OfficeConfig, load_office_config

COUNTERS = ("travel_cm", "deliveries", "acquisitions", "observations", "utterances", "failures",
            "bumps", "reroutes", "false_successes")


_config = config_reader(load_office_config)  # every snapshot of a run carries the same config

@dataclass(frozen=True)
class RobotState:
    id: str
    x: float
    y: float
    heading: float
    speed: float
    place: str                        # the room or corridor it is in
    carrying: tuple[str, ...] = ()
    travelled: float = 0.0            # [m] along its actual motion
    operation: dict[str, Any] = field(default_factory=dict)   # current or last (robot.py)
    route: tuple[tuple[float, float], ...] = ()               # waypoints still ahead [m]
    known_doors: dict[str, list] = field(default_factory=dict)    # door -> [state, cycle seen]
    known_people: dict[str, list] = field(default_factory=dict)   # person -> [room, cycle seen]
    known_obstacles: dict[str, list] = field(default_factory=dict)  # id -> [x, y, radius]
    observations: dict[str, list] = field(default_factory=dict)   # room -> [result, cycle]


@dataclass(frozen=True)
class PersonState:
    id: str
    room: str
    office: str
    x: float
    y: float


@dataclass(frozen=True)
class ItemState:
    id: str
    kind: str
    holder: str                       # a person, room or robot id
    to: str = ""                      # addressee ("" = none)
    temperature: float = 0.0          # [C]; coffee only (0.0 for other kinds)


@dataclass(frozen=True)
class ObstacleState:
    id: str
    x: float
    y: float
    radius: float


@dataclass(frozen=True)
class OfficeSnapshot:
    cycle: int
    time: float
    config: OfficeConfig
    robots: tuple[RobotState, ...] = ()
    people: tuple[PersonState, ...] = ()
    items: tuple[ItemState, ...] = ()
    doors: dict[str, str] = field(default_factory=dict)       # door -> open|closed|blocked
    occupants: dict[str, int] = field(default_factory=dict)   # room -> anonymous people
    obstacles: tuple[ObstacleState, ...] = ()
    counters: dict[str, dict[str, int]] = field(default_factory=dict)
    events: tuple[dict[str, Any], ...] = ()     # what happened during the step into this cycle

    def robot(self, agent: str) -> RobotState:
        for r in self.robots:
            if r.id == agent:
                return r
        raise WorldError(f"office snapshot of cycle {self.cycle}: no robot {agent!r}; "
                         f"robots: {[r.id for r in self.robots]}")

    def item(self, item_id: str) -> ItemState | None:
        return next((i for i in self.items if i.id == item_id), None)

    def to_dict(self) -> dict[str, Any]:
        robots = []
        for r in self.robots:
            d = asdict(r)
            d["carrying"] = list(r.carrying)
            d["route"] = [list(p) for p in r.route]
            robots.append(d)
        return {
            "domain": "office", "cycle": self.cycle, "time": self.time,
            "config": self.config.to_dict(), "robots": robots,
            "people": [dict(vars(p)) for p in self.people],  # flat records of atoms
            "items": [dict(vars(i)) for i in self.items],
            "doors": dict(self.doors), "occupants": dict(self.occupants),
            "obstacles": [dict(vars(o)) for o in self.obstacles],
            "counters": {a: dict(c) for a, c in self.counters.items()},
            "events": [dict(e) for e in self.events],
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> OfficeSnapshot:
        """Rebuild a snapshot from `to_dict` output; raise WorldError naming what is wrong
        (the field, checked against SNAPSHOT, or the config's key)."""
        return rebuild(cls, SNAPSHOT, d, lambda: cls(
            cycle=int(d["cycle"]), time=d["time"], config=_config(d["config"]),
            robots=tuple(_robot(r) for r in d["robots"]),
            people=tuple(record(PersonState, p) for p in d["people"]),
            items=tuple(record(ItemState, i) for i in d["items"]),
            doors=dict(d["doors"]), occupants=dict(d["occupants"]),
            obstacles=tuple(record(ObstacleState, o) for o in d["obstacles"]),
            counters={a: dict(c) for a, c in d["counters"].items()},
            events=tuple(dict(e) for e in d["events"]),
        ))


def _robot(d: dict[str, Any]) -> RobotState:
    r = dict(d)
    r["carrying"] = tuple(r["carrying"])
    r["route"] = tuple(tuple(p) for p in r["route"])
    return record(RobotState, r)


MAX_COORD = 1e4    # [m] a position, either way (the floor is some tens of metres)
_POS, _ID = Num(-MAX_COORD, MAX_COORD), Str()
_SEEN = TupleOf(_ID, Int(), what="[state, cycle seen]")
_OPERATION = Record({"name": _ID, "args": ListOf(Atom(), max_len=8), "status": _ID,
                     "code": Str(), "reason": Str(max_len=4096), "started": Int(),
                     "ended": Int()}, what="an operation")
ROBOT = Record({
    "id": _ID, "x": _POS, "y": _POS, "heading": Num(-1e6, 1e6), "speed": Num(-1e3, 1e3),
    "place": _ID, "carrying": ListOf(_ID), "route": ListOf(TupleOf(_POS, _POS)),
}, {"travelled": Num(), "operation": AnyOf(Record({}), _OPERATION),
    "known_doors": MapOf(_SEEN), "known_people": MapOf(_SEEN),
    "known_obstacles": MapOf(TupleOf(_POS, _POS, Num(0.0, MAX_COORD), what="[x, y, radius]")),
    "observations": MapOf(TupleOf(Atom(), Int(), what="[result, cycle]"))}, what="a robot")
SNAPSHOT = Record({
    "cycle": Int(), "time": Num(), "config": Record({}, open=True), "robots": ListOf(ROBOT),
    "people": ListOf(Record({"id": _ID, "room": _ID, "office": _ID, "x": _POS, "y": _POS},
                            what="a person")),
    "items": ListOf(Record({"id": _ID, "kind": _ID, "holder": _ID},
                           {"to": _ID, "temperature": Num(-1e3, 1e3)}, what="an item")),
    "doors": MapOf(_ID), "occupants": MapOf(Int()),
    "obstacles": ListOf(Record({"id": _ID, "x": _POS, "y": _POS,
                                "radius": Num(0.0, MAX_COORD)}, what="an obstacle")),
    **COMMON,
}, {"domain": OneOf(("office",))}, open=True, what="an office snapshot")
"""The fields of `OfficeSnapshot.to_dict` as perception relies on them (its config, plain
data, is read by load_office_config once per distinct config); other top-level keys are let
through."""
