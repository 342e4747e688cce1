"""The `[world]` table of an office scenario (seed 003) turned into a frozen `OfficeConfig`.

Every key is optional: an empty table gives the default floor of the seed's example (rooms
r-5303, r-5311, r-5313, conference rooms r-5309 and r-5311, mitchell, jhm and others).
The floor is a ring: two corridors (c-south, c-north) joined at both ends (c-west, c-east),
one row of rooms south of c-south and one north of c-north, laid out west to east, each
room with one door onto its corridor. `OfficeConfig.to_dict()` is read back by
`load_office_config` to an equal config, so a snapshot carries its floor as plain data.
Units: m, m/s, s, degrees Celsius.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace
from typing import Any

from world.errors import ConfigError

DOOR_STATES = ("open", "closed", "blocked")
CORRIDORS = ("c-south", "c-north")


@dataclass(frozen=True)
class RoomSpec:
    """A room of a row; `occupants` are anonymous people in it (a meeting)."""

    id: str
    kind: str = "office"
    width: float = 6.0
    number: int = 0
    door: str = "open"
    occupants: int = 0


@dataclass(frozen=True)
class FireDoorSpec:
    """A door across a corridor, `at` [m] from the floor's west edge."""

    id: str
    corridor: str
    at: float
    state: str = "open"


@dataclass(frozen=True)
class PersonSpec:
    id: str
    room: str
    office: str = ""


@dataclass(frozen=True)
class ItemSpec:
    """An item held by a person or lying in a room; `to`: its addressee (person or room, or
    ""); `temperature` [C] for coffee (0: brewed hot)."""

    id: str
    kind: str
    holder: str
    to: str = ""
    temperature: float = 0.0


@dataclass(frozen=True)
class RobotStart:
    agent: str
    room: str


def _rooms(*entries: tuple[str, str, float]) -> tuple[RoomSpec, ...]:
    return tuple(RoomSpec(i, kind, width, int(i[2:])) for i, kind, width in entries)


DEFAULT_SOUTH = _rooms(("r-5301", "office", 6), ("r-5303", "office", 6), ("r-5305", "office", 6),
                       ("r-5307", "office", 6), ("r-5309", "conference", 8),
                       ("r-5311", "conference", 8), ("r-5313", "mailroom", 6),
                       ("r-5315", "office", 6), ("r-5317", "office", 6))
DEFAULT_SOUTH = tuple(replace(r, occupants=4) if r.id == "r-5309" else r for r in DEFAULT_SOUTH)
DEFAULT_NORTH = _rooms(("r-5302", "kitchen", 6), ("r-5304", "office", 6), ("r-5306", "lab", 8),
                       ("r-5308", "office", 6), ("r-5310", "lounge", 8), ("r-5312", "office", 6),
                       ("r-5314", "printer", 4), ("r-5316", "office", 8),
                       ("r-5318", "office", 6))
DEFAULT_FIRE_DOORS = (FireDoorSpec("d-south", "c-south", 26.0),
                      FireDoorSpec("d-north", "c-north", 22.0))
DEFAULT_PEOPLE = tuple(PersonSpec(p, r, r) for p, r in (
    ("rich", "r-5301"), ("mitchell", "r-5303"), ("mmv", "r-5305"), ("sven", "r-5307"),
    ("jhm", "r-5311"), ("khaigh", "r-5313"), ("reid", "r-5315"), ("joseph", "r-5304"),
    ("rgoodwin", "r-5312")))
DEFAULT_ITEMS = (ItemSpec("mail-mitchell", "mail", "mitchell", "r-5313"),
                 ItemSpec("fax-jhm", "fax", "jhm", "r-5313"),
                 ItemSpec("mail-reid", "mail", "khaigh", "reid"),
                 ItemSpec("coffee-1", "coffee", "r-5302"))


@dataclass(frozen=True)
class OfficeConfig:
    """The floor, its people and items, the robots' starts and the physical constants."""

    south: tuple[RoomSpec, ...] = DEFAULT_SOUTH
    north: tuple[RoomSpec, ...] = DEFAULT_NORTH
    fire_doors: tuple[FireDoorSpec, ...] = DEFAULT_FIRE_DOORS
    people: tuple[PersonSpec, ...] = DEFAULT_PEOPLE
    items: tuple[ItemSpec, ...] = DEFAULT_ITEMS
    robots: tuple[RobotStart, ...] = ()
    corridor_width: float = 2.0   # [m]
    room_depth: float = 8.0       # [m]
    middle_depth: float = 6.0     # [m] the block between the two corridors
    door_width: float = 1.0       # [m] room doors
    dt: float = 0.5               # [s] one cycle
    substeps: int = 5             # pymunk steps per cycle
    speed: float = 1.0            # [m/s] the robot's cruising speed
    sight: float = 3.0            # [m] doors and obstacles are seen this far
    handover: float = 3.0         # [s] to take or give an item
    observe_time: float = 2.0     # [s] to look into a room
    progress_time: float = 5.0    # [s] without 0.1 m of progress: navigation fails
    capacity: int = 4             # items the robot can carry
    coffee_brew: float = 75.0     # [C] fresh coffee (kept so in a kitchen)
    coffee_ambient: float = 21.0  # [C] room temperature
    coffee_cold: float = 45.0     # [C] below this coffee is cold
    coffee_tau: float = 300.0     # [s] cooling time constant (Newton's law)
    wander_rate: float = 0.0      # [1/s] chance per second that a person leaves the office
    wander_time: float = 60.0     # [s] a wandering person's time away
    distances: bool = True        # perceive room-to-room path distances

    def to_dict(self) -> dict[str, Any]:
        """Plain data in the `[world]` table's own schema."""
        d = asdict(self)
        for key in ("south", "north", "fire_doors", "people", "items", "robots"):
            d[key] = [dict(x) for x in d[key]]
        return d

    @property
    def rooms(self) -> tuple[RoomSpec, ...]:
        return self.south + self.north


_FLOATS = {"corridor_width": (1.0, 10.0), "room_depth": (2.0, 50.0), "middle_depth": (1.0, 100.0),
           "door_width": (0.7, 3.0), "dt": (0.01, 2.0), "speed": (0.1, 5.0),
           "sight": (0.5, 50.0), "handover": (0.0, 600.0), "observe_time": (0.0, 600.0),
           "progress_time": (0.5, 600.0), "coffee_brew": (0.0, 100.0),
           "coffee_ambient": (-20.0, 50.0), "coffee_cold": (0.0, 100.0),
           "coffee_tau": (1.0, 1e6), "wander_rate": (0.0, 10.0), "wander_time": (0.0, 1e6)}
_INTS = {"substeps": (1, 50), "capacity": (1, 100)}
_LISTS = ("south", "north", "fire_doors", "people", "items", "robots")
_KNOWN = set(_FLOATS) | set(_INTS) | set(_LISTS) | {"distances"}


def _number(value: Any, where: str, lo: float, hi: float, kind: type) -> Any:
    ok = (int,) if kind is int else (int, float)
    if isinstance(value, bool) or not isinstance(value, ok) or not lo <= value <= hi:
        raise ConfigError(f"[world] {where}: expected {kind.__name__} in [{lo:g}, {hi:g}], "
                          f"got {value!r}")
    return kind(value)


def _entry(item: Any, where: str, spec: type, required: tuple[str, ...],
           types: dict[str, type]) -> Any:
    if isinstance(item, str) and spec is RoomSpec:
        item = {"id": item}
    if not isinstance(item, dict):
        raise ConfigError(f"[world] {where}: expected a table, got {item!r}")
    unknown = set(item) - set(types)
    if unknown:
        raise ConfigError(f"[world] {where}: unknown keys {sorted(unknown)}; "
                          f"known: {sorted(types)}")
    for key in required:
        if key not in item:
            raise ConfigError(f"[world] {where}: missing key {key!r}")
    values = {}
    for key, value in item.items():
        kind = types[key]
        if kind is float:
            values[key] = _number(value, f"{where}.{key}", -1e9, 1e9, float)
        elif kind is int:
            values[key] = _number(value, f"{where}.{key}", 0, 10**6, int)
        elif not isinstance(value, str) or (not value and key in required):
            raise ConfigError(f"[world] {where}.{key}: expected a non-empty string, got {value!r}")
        else:
            values[key] = value
    return spec(**values)


def _room(item: Any, where: str) -> RoomSpec:
    r = _entry(item, where, RoomSpec, ("id",), {"id": str, "kind": str, "width": float,
                                                "number": int, "door": str, "occupants": int})
    if not 2.0 <= r.width <= 50.0:
        raise ConfigError(f"[world] {where}.width: expected [m] in [2, 50], got {r.width}")
    if r.door not in DOOR_STATES:
        raise ConfigError(f"[world] {where}.door: expected one of {DOOR_STATES}, got {r.door!r}")
    digits = "".join(c for c in r.id if c.isdigit())[:9]
    return replace(r, number=r.number or int(digits or 0))


def _parse_lists(d: dict[str, Any]) -> dict[str, tuple]:
    out: dict[str, tuple] = {}
    for key in _LISTS:
        if key in d and not isinstance(d[key], list):
            raise ConfigError(f"[world] {key}: expected a list, got {d[key]!r}")
    for row in ("south", "north"):
        if row in d:
            out[row] = tuple(_room(x, f"{row}[{k}]") for k, x in enumerate(d[row]))
    specs = {"fire_doors": (FireDoorSpec, ("id", "corridor", "at"),
                            {"id": str, "corridor": str, "at": float, "state": str}),
             "people": (PersonSpec, ("id", "room"), {"id": str, "room": str, "office": str}),
             "items": (ItemSpec, ("id", "kind", "holder"), {"id": str, "kind": str,
                                                            "holder": str, "to": str,
                                                            "temperature": float}),
             "robots": (RobotStart, ("agent", "room"), {"agent": str, "room": str})}
    for key, (spec, required, types) in specs.items():
        if key in d:
            out[key] = tuple(_entry(x, f"{key}[{k}]", spec, required, types)
                             for k, x in enumerate(d[key]))
    if "people" in out:
        out["people"] = tuple(p if p.office else replace(p, office=p.room) for p in out["people"])
    return out


def load_office_config(d: dict[str, Any] | None) -> OfficeConfig:
    """Read the `[world]` table (a dict, as tomllib gives it); raise ConfigError naming the key."""
    d = dict(d or {})
    unknown = set(d) - _KNOWN
    if unknown:
        raise ConfigError(f"[world] unknown keys {sorted(unknown)}; known: {sorted(_KNOWN)}")
    values: dict[str, Any] = {k: _number(d[k], k, lo, hi, float)
                              for k, (lo, hi) in _FLOATS.items() if k in d}
    values.update({k: _number(d[k], k, lo, hi, int) for k, (lo, hi) in _INTS.items() if k in d})
    if "distances" in d:
        if not isinstance(d["distances"], bool):
            raise ConfigError(f"[world] distances: expected true or false, got {d['distances']!r}")
        values["distances"] = d["distances"]
    values.update(_parse_lists(d))
    config = OfficeConfig(**values)
    check_references(config)
    return config


def check_references(config: OfficeConfig) -> None:
    """Ids unique, every name refers to something that exists (raises ConfigError)."""
    rooms = {r.id for r in config.rooms}
    if not config.south and not config.north:
        raise ConfigError("[world] south, north: expected at least one room, got none")
    names = ([r.id for r in config.rooms] + [f.id for f in config.fire_doors]
             + [p.id for p in config.people] + [i.id for i in config.items]
             + [f"d-{r.id.removeprefix('r-')}" for r in config.rooms] + list(CORRIDORS))
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise ConfigError(f"[world] ids used twice (rooms, doors, people, items): {twice}")
    people = {p.id for p in config.people}
    for f in config.fire_doors:
        if f.corridor not in CORRIDORS or f.state not in DOOR_STATES:
            raise ConfigError(f"[world] fire door {f.id}: corridor must be one of {CORRIDORS} and "
                              f"state one of {DOOR_STATES}, got {f.corridor!r}, {f.state!r}")
    for p in config.people:
        for where in (p.room, p.office):
            if where not in rooms:
                raise ConfigError(f"[world] person {p.id}: unknown room {where!r}")
    for i in config.items:
        if i.holder not in rooms | people:
            raise ConfigError(f"[world] item {i.id}: holder {i.holder!r} is neither a room nor a "
                              f"person")
        if i.to and i.to not in rooms | people:
            raise ConfigError(f"[world] item {i.id}: to {i.to!r} is neither a room nor a person")
    for r in config.robots:
        if r.room not in rooms:
            raise ConfigError(f"[world] robot {r.agent}: unknown room {r.room!r}")
    if len({r.agent for r in config.robots}) != len(config.robots):
        raise ConfigError("[world] robots: an agent has two start rooms")
    if config.coffee_cold >= config.coffee_brew:
        raise ConfigError(f"[world] coffee_cold: expected below coffee_brew "
                          f"({config.coffee_brew:g} C), got {config.coffee_cold:g} C")
