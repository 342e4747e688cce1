"""World configuration: the `[world]` table of a scenario TOML turned into a frozen `WorldConfig`.

Every key is optional; absent keys give the default city (4 x 4 streets, 100 m blocks).
`WorldConfig.to_dict()` returns a dict that `load_world_config` reads back to an equal config,
so a snapshot can carry its city as plain data. Units: m, m/s, s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from world.errors import ConfigError

NS_NAMES = ("A", "B", "C", "D", "E", "F", "G", "H", "J", "K", "L", "M")
EW_NAMES = ("FIRST", "SECOND", "THIRD", "FOURTH", "FIFTH", "SIXTH", "SEVENTH", "EIGHTH",
            "NINTH", "TENTH", "ELEVENTH", "TWELFTH")


@dataclass(frozen=True)
class PackageSpec:
    """A package to deliver to building `address` on `street`, carried by agent `owner`."""

    id: str
    address: int
    street: str
    owner: str


@dataclass(frozen=True)
class CarStart:
    """Where an agent's car starts: in the right lane of `street`, `along` [m] from the centre of
    its crossing with `from_street`, heading toward `toward` (a crossing street)."""

    agent: str
    street: str
    from_street: str
    toward: str
    along: float = 20.0
    speed: float = 0.0


@dataclass(frozen=True)
class WorldConfig:
    """The city and its population. Lettered streets run north-south (x = i * block_length),
    ordinal streets run east-west (y = j * block_length)."""

    ns_streets: tuple[str, ...] = NS_NAMES[:4]
    ew_streets: tuple[str, ...] = EW_NAMES[:4]
    block_length: float = 100.0      # [m] between street centrelines
    speed_limit: float = 15.0        # [m/s]
    pedestrians: int = 12
    traffic: int = 4                 # simulator-driven vehicles
    packages: tuple[PackageSpec, ...] = ()
    cars: tuple[CarStart, ...] = ()
    perception_range: float = 60.0   # [m]
    dt: float = 0.1                  # [s] fixed step
    crossing_rate: float = 0.02      # [1/s] chance per second that a walking pedestrian crosses

    def to_dict(self) -> dict[str, Any]:
        """Plain data in the `[world]` table's own schema (load_world_config reads it back)."""
        return {
            "ns_streets": list(self.ns_streets), "ew_streets": list(self.ew_streets),
            "block_length": self.block_length, "speed_limit": self.speed_limit,
            "pedestrians": self.pedestrians, "traffic": self.traffic,
            "packages": [{"id": p.id, "address": p.address, "street": p.street, "owner": p.owner}
                         for p in self.packages],
            "cars": [{"agent": c.agent, "street": c.street, "from": c.from_street,
                      "toward": c.toward, "along": c.along, "speed": c.speed} for c in self.cars],
            "perception_range": self.perception_range, "dt": self.dt,
            "crossing_rate": self.crossing_rate,
        }


_FLOATS = {"block_length": (40.0, 400.0), "speed_limit": (1.0, 60.0),
           "perception_range": (5.0, 1000.0), "dt": (0.005, 1.0), "crossing_rate": (0.0, 10.0)}
_INTS = {"pedestrians": (0, 10000), "traffic": (0, 10000)}
_KNOWN = set(_FLOATS) | set(_INTS) | {"ns_streets", "ew_streets", "grid", "packages", "cars"}


def _number(d: dict, key: str, lo: float, hi: float, kind: type) -> Any:
    value = d[key]
    ok_types = (int,) if kind is int else (int, float)
    if isinstance(value, bool) or not isinstance(value, ok_types) or not lo <= value <= hi:
        raise ConfigError(f"[world] {key}: expected {kind.__name__} in [{lo}, {hi}], got {value!r}")
    return kind(value)


def _names(d: dict, key: str, default: tuple[str, ...]) -> tuple[str, ...]:
    if key not in d:
        return default
    names = d[key]
    if (not isinstance(names, list | tuple) or len(names) < 2
            or not all(isinstance(n, str) and n for n in names) or len(set(names)) != len(names)):
        raise ConfigError(f"[world] {key}: expected >= 2 distinct street names, got {names!r}")
    return tuple(names)


def _grid(d: dict) -> tuple[tuple[str, ...], tuple[str, ...]]:
    ns, ew = NS_NAMES[:4], EW_NAMES[:4]
    if "grid" in d:
        grid = d["grid"]
        if (not isinstance(grid, list | tuple) or len(grid) != 2
                or not all(isinstance(g, int) and 2 <= g <= len(NS_NAMES) for g in grid)):
            raise ConfigError(f"[world] grid: expected [columns, rows] each in 2..12, got {grid!r}")
        ns, ew = NS_NAMES[:grid[0]], EW_NAMES[:grid[1]]
    ns, ew = _names(d, "ns_streets", ns), _names(d, "ew_streets", ew)
    if set(ns) & set(ew):
        raise ConfigError(f"[world] street names used twice: {sorted(set(ns) & set(ew))}")
    return ns, ew


def _record(item: Any, where: str, fields: dict[str, type]) -> dict:
    if not isinstance(item, dict):
        raise ConfigError(f"[world] {where}: expected a table, got {item!r}")
    for name, kind in fields.items():
        if name not in item:
            raise ConfigError(f"[world] {where}: missing key {name!r}")
        value = item[name]
        if isinstance(value, bool) or not isinstance(value, kind):
            raise ConfigError(f"[world] {where}.{name}: expected {kind}, got {value!r}")
    return item


def _tables(d: dict, key: str) -> list:
    """``d[key]``, a list of tables ([] when absent); ConfigError when it is no list."""
    items = d.get(key, [])
    if not isinstance(items, list):
        raise ConfigError(f"[world] {key}: expected a list of tables, got {items!r:.60}")
    return items


def _packages(d: dict) -> tuple[PackageSpec, ...]:
    out = []
    for k, item in enumerate(_tables(d, "packages")):
        fields = {"id": str, "address": int, "street": str, "owner": str}
        r = _record(item, f"packages[{k}]", fields)
        out.append(PackageSpec(r["id"], r["address"], r["street"], r["owner"]))
    return tuple(out)


def _cars(d: dict) -> tuple[CarStart, ...]:
    out = []
    for k, item in enumerate(_tables(d, "cars")):
        r = _record(item, f"cars[{k}]", {"agent": str, "street": str, "from": str, "toward": str})
        along, speed = r.get("along", 20.0), r.get("speed", 0.0)
        for key, value in (("along", along), ("speed", speed)):
            if isinstance(value, bool) or not isinstance(value, int | float) or value < 0:
                raise ConfigError(f"[world] cars[{k}].{key}: expected number >= 0, got {value!r}")
        out.append(CarStart(r["agent"], r["street"], r["from"], r["toward"],
                            float(along), float(speed)))
    return tuple(out)


def load_world_config(d: dict | None) -> WorldConfig:
    """Read the `[world]` table (a dict, as tomllib gives it); raise ConfigError naming the key."""
    d = dict(d or {})
    unknown = set(d) - _KNOWN
    if not unknown:
        return _read_known(d)
    first = f"[world] unknown keys {sorted(unknown)}; known: {sorted(_KNOWN)}"
    try:   # the rest is read too, so a check names its errors as well
        _read_known({k: v for k, v in d.items() if k in _KNOWN})
    except ConfigError as exc:
        raise ConfigError(f"{first}\n{exc}") from None
    raise ConfigError(first)


def _read_known(d: dict) -> WorldConfig:
    """The table read, its keys all known."""
    ns, ew = _grid(d)
    values: dict[str, Any] = {k: _number(d, k, lo, hi, float)
                              for k, (lo, hi) in _FLOATS.items() if k in d}
    values.update({k: _number(d, k, lo, hi, int) for k, (lo, hi) in _INTS.items() if k in d})
    config = WorldConfig(ns_streets=ns, ew_streets=ew, packages=_packages(d), cars=_cars(d),
                         **values)
    _check_references(config)
    return config


def _check_references(config: WorldConfig) -> None:
    streets = set(config.ns_streets) | set(config.ew_streets)
    for c in config.cars:
        for name in (c.street, c.from_street, c.toward):
            if name not in streets:
                raise ConfigError(f"[world] car {c.agent}: unknown street {name!r}")
        if (c.street in config.ns_streets) == (c.from_street in config.ns_streets) or \
                (c.street in config.ns_streets) == (c.toward in config.ns_streets):
            raise ConfigError(f"[world] car {c.agent}: from/toward must cross street {c.street}")
        if c.from_street == c.toward:
            raise ConfigError(f"[world] car {c.agent}: from and toward are both {c.toward}")
    if len({c.agent for c in config.cars}) != len(config.cars):
        raise ConfigError("[world] cars: an agent has two start positions")
    for p in config.packages:
        if p.street not in streets:
            raise ConfigError(f"[world] package {p.id}: unknown street {p.street!r}")
