"""The `[world]` table of a Blocks World scenario turned into a frozen `BlocksConfig`.

Every key is optional: an empty table gives seed 000's Figure 3 (C on B on A on the table T,
blocks 2 m x 2 m, a table of six columns 3 m apart, 2 m high). Units: m, s. The keys and their
meaning are documented in docs/scenarios.md (section "The Blocks World").
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from typing import Any

from world.blocks.towers import random_towers
from world.errors import ConfigError

NAME = re.compile(r"[A-Za-z][A-Za-z0-9_-]*\Z")
RESERVED = ("empty", "floor")   # a free hand's status; what a fallen block may lie on
FIGURE3 = (("A", "B", "C"),)
_KNOWN = {"table", "block_size", "sizes", "towers", "random_towers", "offsets", "holding",
          "resolution", "dt"}


@dataclass(frozen=True)
class TableSpec:
    """The table: `columns` places for towers, `pitch` [m] apart, column 0 at x = 0; its top is
    `height` [m] above the floor (y = 0). Unless a scenario says otherwise it has 6 columns,
    or one more than there are blocks, so every block fits on it side by side."""

    name: str = "T"
    columns: int = 6
    pitch: float = 3.0
    height: float = 2.0

    def column_x(self, k: int) -> float:
        """The x [m] of column k's centre."""
        return k * self.pitch

    @property
    def span(self) -> tuple[float, float]:
        """The table top's left and right ends [m]."""
        return -self.pitch / 2, (self.columns - 0.5) * self.pitch


@dataclass(frozen=True)
class BlockSpec:
    """A block's name and size [m]."""

    name: str
    width: float = 2.0
    height: float = 2.0


@dataclass(frozen=True)
class BlocksConfig:
    """A whole Blocks World: the table, the blocks, how they stand (towers, bottom first, tower
    k in column k; an empty tower leaves its column free), the blocks agents start holding,
    and the percept resolution [m] and cycle length dt [s]."""

    table: TableSpec = field(default_factory=TableSpec)
    blocks: tuple[BlockSpec, ...] = tuple(BlockSpec(n) for n in "ABC")
    towers: tuple[tuple[str, ...], ...] = FIGURE3
    offsets: dict[str, float] = field(default_factory=dict)    # [m] from the support's centre
    holding: dict[str, str] = field(default_factory=dict)      # agent -> block
    resolution: float = 0.25
    dt: float = 0.5

    def block(self, name: str) -> BlockSpec:
        return next(b for b in self.blocks if b.name == name)


def load_blocks_config(table: dict[str, Any], seed: int = 0) -> BlocksConfig:
    """Check and read a `[world]` table (without `domain`); `seed` draws `random_towers` when
    it gives none. Raises ConfigError naming the key, the expected and the actual value."""
    if not isinstance(table, dict):
        raise ConfigError(f"[world]: expected a table, got {table!r:.60}")
    unknown = sorted(set(table) - _KNOWN)
    if unknown:
        raise ConfigError(f"[world]: unknown keys {unknown}; known: {sorted(_KNOWN)}")
    resolution = _number(table, "resolution", 0.25, 1 / 64, 4.0)
    if 2.0 ** round(math.log2(resolution)) != resolution:
        raise ConfigError(f"[world] resolution: expected a power of two [m] (0.25, 0.5, 1, ...) "
                          f"so that percept sums are exact, got {resolution}")
    spec = _table(table.get("table", {}), resolution)
    size = _size(table.get("block_size", [2.0, 2.0]), "block_size", resolution)
    towers = _towers(table, seed, spec)
    holding = _holding(table.get("holding", {}))
    names = [n for t in towers for n in t] + list(holding.values())
    _unique(names, spec.name)
    if "columns" not in table.get("table", {}):     # room for every block on the table
        spec = replace(spec, columns=max(spec.columns, len(names) + 1))
    sizes = _dict(table, "sizes")
    extra = sorted(set(sizes) - set(names))
    if extra:
        raise ConfigError(f"[world] sizes: blocks {extra} stand in no tower and no hand; "
                          f"blocks: {sorted(names)}")
    blocks = tuple(BlockSpec(n, *(_size(sizes[n], f"sizes.{n}", resolution) if n in sizes
                                  else size)) for n in sorted(names))
    offsets = {n: _number(_dict(table, "offsets"), n, 0.0, -100.0, 100.0, "offsets.")
               for n in _dict(table, "offsets")}
    missing = sorted(set(offsets) - {n for t in towers for n in t})
    if missing:
        raise ConfigError(f"[world] offsets: {missing} stand in no tower")
    config = BlocksConfig(spec, blocks, towers, offsets, holding, resolution,
                          _number(table, "dt", 0.5, 0.05, 5.0))
    _check_layout(config)
    return config


def _number(table: dict, key: str, default: float, lo: float, hi: float,
            prefix: str = "") -> float:
    value = table.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not lo <= value <= hi:
        raise ConfigError(f"[world] {prefix}{key}: expected a number in [{lo:g}, {hi:g}], "
                          f"got {value!r}")
    return float(value)


def _dict(table: dict, key: str) -> dict:
    value = table.get(key, {})
    if not isinstance(value, dict):
        raise ConfigError(f"[world] {key}: expected a table {{NAME = ...}}, got {value!r:.60}")
    return value


def _multiple(value: float, resolution: float, where: str) -> float:
    if abs(value / resolution - round(value / resolution)) > 1e-9:
        raise ConfigError(f"[world] {where}: expected a multiple of the resolution "
                          f"{resolution} [m], got {value}")
    return value


def _table(table: Any, resolution: float) -> TableSpec:
    if not isinstance(table, dict):
        raise ConfigError(f"[world] table: expected {{name, columns, pitch, height}}, "
                          f"got {table!r:.60}")
    unknown = sorted(set(table) - {"name", "columns", "pitch", "height"})
    if unknown:
        raise ConfigError(f"[world] table: unknown keys {unknown}; known: "
                          f"['columns', 'height', 'name', 'pitch']")
    name = table.get("name", "T")
    if not isinstance(name, str) or not NAME.match(name) or name in RESERVED:
        raise ConfigError(f"[world] table.name: expected a symbol such as 'T', got {name!r}")
    columns = table.get("columns", 6)
    if isinstance(columns, bool) or not isinstance(columns, int) or not 1 <= columns <= 64:
        raise ConfigError(f"[world] table.columns: expected an integer in [1, 64], "
                          f"got {columns!r}")
    pitch = _multiple(_number(table, "pitch", 3.0, 0.25, 50.0, "table."), resolution,
                      "table.pitch")
    height = _multiple(_number(table, "height", 2.0, 0.25, 50.0, "table."), resolution,
                       "table.height")
    return TableSpec(name, columns, pitch, height)


def _size(value: Any, where: str, resolution: float) -> tuple[float, float]:
    if (not isinstance(value, list) or len(value) != 2
            or any(isinstance(v, bool) or not isinstance(v, int | float) or not 0.25 <= v <= 20
                   for v in value)):
        raise ConfigError(f"[world] {where}: expected [width, height] in [0.25, 20] [m], "
                          f"got {value!r:.60}")
    return tuple(_multiple(float(v), resolution, where) for v in value)  # type: ignore


def _towers(table: dict, seed: int, spec: TableSpec) -> tuple[tuple[str, ...], ...]:
    if "towers" in table and "random_towers" in table:
        raise ConfigError("[world]: give towers or random_towers, not both")
    if "random_towers" in table:
        return random_towers(table["random_towers"], seed, spec.columns, spec.name)
    towers = table.get("towers", [list(t) for t in FIGURE3])
    if not isinstance(towers, list) or not all(isinstance(t, list) for t in towers):
        raise ConfigError(f"[world] towers: expected a list of towers, each a list of block "
                          f"names bottom first (e.g. [[\"A\", \"B\", \"C\"]]), got {towers!r:.60}")
    if "columns" in table.get("table", {}) and len(towers) > spec.columns:
        raise ConfigError(f"[world] towers: {len(towers)} towers on a table of "
                          f"{spec.columns} columns; add columns (table.columns)")
    for k, tower in enumerate(towers):
        for j, name in enumerate(tower):
            _name(name, f"towers[{k}][{j}]")
    return tuple(tuple(t) for t in towers)


def _name(name: Any, where: str) -> str:
    if not isinstance(name, str) or not NAME.match(name) or name in RESERVED:
        raise ConfigError(f"[world] {where}: expected a block name (a symbol such as 'A', "
                          f"not {list(RESERVED)}), got {name!r}")
    return name


def _holding(value: Any) -> dict[str, str]:
    if not isinstance(value, dict):
        raise ConfigError(f"[world] holding: expected {{AGENT = BLOCK}}, got {value!r:.60}")
    return {agent: _name(block, f"holding.{agent}") for agent, block in value.items()}


def _unique(names: list[str], table: str) -> None:
    seen: set[str] = {table}
    for n in names:
        if n in seen:
            raise ConfigError(f"[world] towers/holding: block {n} appears twice (or names "
                              f"the table); each block stands in one place")
        seen.add(n)


def _check_layout(config: BlocksConfig) -> None:
    """The bottom blocks must stand on the table and towers must not overlap one another."""
    spec, previous = config.table, None
    lo, hi = spec.span
    for k, tower in enumerate(config.towers):
        if not tower:
            continue
        spans = tower_spans(config, k)
        x0, x1 = spans[0]
        if x0 < lo - 1e-9 or x1 > hi + 1e-9:
            raise ConfigError(f"[world] towers[{k}]: {tower[0]} ({x0:g} .. {x1:g} m) hangs over "
                              f"the table's end ({lo:g} .. {hi:g} m); widen table.pitch or "
                              f"use another column")
        left = min(a for a, _ in spans)
        if previous is not None and left < previous[0] - 1e-9:
            raise ConfigError(f"[world] towers[{k}]: {list(tower)} overlaps {previous[1]}; "
                              f"leave a column free ([] in towers) or widen table.pitch")
        previous = (max(b for _, b in spans), list(tower))


def tower_spans(config: BlocksConfig, k: int) -> list[tuple[float, float]]:
    """The x extent [m] of each block of tower k, bottom first (offsets add up the tower)."""
    x, spans = config.table.column_x(k), []
    for name in config.towers[k]:
        x += config.offsets.get(name, 0.0)
        w = config.block(name).width
        spans.append((x - w / 2, x + w / 2))
    return spans
