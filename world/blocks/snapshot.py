"""The observable Blocks World of one cycle as frozen dataclasses with an exact plain-data round
trip (`to_dict` / `from_dict`: str/int/float/list/dict only, msgpack- and JSON-able).

Units: positions [m] (x to the right, y up, the floor at y = 0), angles [deg] counter-clockwise,
time [s]. A block's (x, y) is its centre; a held block is where the gripper holds it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

from bus.schema import Int, ListOf, Num, OneOf, Record, Str, brief
from world.base import COMMON, rebuild, record
from world.blocks.config import TableSpec
from world.errors import WorldError

DOMAIN_NAME = "blocks"
COUNTERS = ("actions_done", "actions_failed", "blocks_moved", "blocks_dropped")


@dataclass(frozen=True)
class BlockState:
    """A block: centre (x, y) [m], angle [deg], size [m]; `held_by` names the agent whose
    gripper holds it ("" when it stands or lies somewhere)."""

    name: str
    x: float
    y: float
    angle: float
    width: float
    height: float
    held_by: str = ""


@dataclass(frozen=True)
class HandState:
    """An agent's gripper: its hand id (H1, H2, ... in agent order), where it is [m] and the
    block it holds ("" when empty)."""

    agent: str
    hand: str
    x: float
    y: float
    holding: str = ""


@dataclass(frozen=True)
class BlocksSnapshot:
    """The state of cycle `cycle`; `events` are what happened during the step into it."""

    cycle: int
    time: float
    table: TableSpec
    resolution: float
    blocks: tuple[BlockState, ...] = ()
    hands: tuple[HandState, ...] = ()
    counters: dict[str, dict[str, int]] = field(default_factory=dict)
    events: tuple[dict[str, Any], ...] = ()

    def hand(self, agent: str) -> HandState:
        """The agent's gripper; raises WorldError naming the agents there are."""
        for h in self.hands:
            if h.agent == agent:
                return h
        raise WorldError(f"blocks snapshot of cycle {self.cycle}: no agent {agent!r}; "
                         f"agents: {[h.agent for h in self.hands]}")

    def to_dict(self) -> dict[str, Any]:
        return {
            "domain": DOMAIN_NAME, "cycle": self.cycle, "time": self.time,
            "table": asdict(self.table), "resolution": self.resolution,
            "blocks": [asdict(b) for b in self.blocks],
            "hands": [asdict(h) for h in self.hands],
            "counters": {a: dict(c) for a, c in self.counters.items()},
            "events": [dict(e) for e in self.events],
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> BlocksSnapshot:
        """Rebuild a snapshot from `to_dict` output; raises WorldError naming what is wrong."""
        if not isinstance(d, dict) or d.get("domain") != DOMAIN_NAME:
            raise WorldError(f"BlocksSnapshot.from_dict: expected a dict with domain "
                             f"{DOMAIN_NAME!r}, got {brief(d)}")
        return rebuild(cls, SNAPSHOT, d, lambda: cls(
            cycle=int(d["cycle"]), time=float(d["time"]),
            table=record(TableSpec, d["table"]), resolution=float(d["resolution"]),
            blocks=tuple(record(BlockState, b) for b in d["blocks"]),
            hands=tuple(record(HandState, h) for h in d["hands"]),
            counters={a: dict(c) for a, c in d["counters"].items()},
            events=tuple(dict(e) for e in d["events"]),
        ))


MAX_COORD = 1e4    # [m] a position or size, either way (the table is a few metres wide)
_POS = Num(-MAX_COORD, MAX_COORD)
_SIZE = Num(1e-3, MAX_COORD)
SNAPSHOT = Record({
    "domain": OneOf((DOMAIN_NAME,)), "cycle": Int(), "time": Num(),
    "table": Record({}, {"name": Str(), "columns": Int(1, 10**4), "pitch": _SIZE,
                         "height": _SIZE}, what="a table"),
    "resolution": Num(1e-3, 10.0),
    "blocks": ListOf(Record({"name": Str(), "x": _POS, "y": _POS, "angle": Num(-1e6, 1e6),
                             "width": _SIZE, "height": _SIZE}, {"held_by": Str()},
                            what="a block")),
    "hands": ListOf(Record({"agent": Str(), "hand": Str(), "x": _POS, "y": _POS},
                           {"holding": Str()}, what="a hand")),
    **COMMON,
}, open=True, what="a blocks snapshot")
"""The fields of `BlocksSnapshot.to_dict` as perception relies on them (positions within
MAX_COORD, so its arithmetic stays finite); other top-level keys are let through."""
