"""Scenario events and faults in the Blocks World (`[[events]]`, `teleo event`). Never raises:
a bad event gives {"event": ..., "status": "failed", "reason": ...} and changes nothing.

Kinds:
- {"kind": "add", "block": NAME, "on": TABLE|BLOCK (default the table), "size": [w, h] [m]
   (default 2 x 2), "offset": dx [m] from the support's centre (default 0), "column": k (on
   the table; default the leftmost free)}: a person sets a new block down. Set off-centre on a
   block it may not be held up: then it falls.
- {"kind": "remove", "block": NAME}: a person takes away a block with nothing on it.
- {"kind": "knock", "block": NAME, "speed": v [m/s] (+ = right, default 3)}: a push that sends
  the block (and what stands on it) sideways: off its tower, perhaps off the table.
- {"kind": "slip", "agent": AGENT}: the agent's gripper loses its block, which falls from where
  it was held (counted in the agent's blocks_dropped).
"""

from __future__ import annotations

import math
from typing import Any, Protocol

from world.blocks.block import Block, Box
from world.blocks.config import NAME, RESERVED, BlocksConfig
from world.blocks.gripper import Gripper
from world.errors import WorldError

KINDS = ("add", "remove", "knock", "slip")
FIELDS = {"add": {"block", "on", "size", "offset", "column"}, "remove": {"block"},
          "knock": {"block", "speed"}, "slip": {"agent"}}


class World(Protocol):
    """The part of simulation.BlocksWorld that events change."""

    config: BlocksConfig
    blocks: dict[str, Block]
    grippers: dict[str, Gripper]

    def holder(self, name: str) -> Gripper | None: ...
    def on_top_of(self, block: Block) -> list[str]: ...
    def obstacle(self, box: Box, ignore: Block | None = None) -> str | None: ...
    def add_block(self, name: str, width: float, height: float) -> Block: ...
    def remove_block(self, block: Block) -> None: ...
    def drop(self, gripper: Gripper) -> Block: ...
    def note(self, kind: str, **fields: Any) -> None: ...


def apply_event(world: World, event: Any) -> dict[str, Any]:
    """Apply one event; return its outcome."""
    try:
        if not isinstance(event, dict):
            raise WorldError(f"expected a dict with a 'kind', got {event!r:.80}")
        kind = event.get("kind")
        if kind not in KINDS:
            raise WorldError(f"unknown kind {kind!r}; known: {' '.join(KINDS)}")
        unknown = sorted(set(event) - FIELDS[kind] - {"kind"})
        if unknown:
            raise WorldError(f"{kind}: unknown fields {unknown}; known: {sorted(FIELDS[kind])}")
        _DO[kind](world, event)
    except WorldError as exc:
        return {"event": event, "status": "failed", "reason": f"inject: {exc}"}
    return {"event": event, "status": "done", "reason": ""}


MAX_OFFSET = 20.0   # [m] an added block's offset from its support's centre
MAX_KNOCK = 30.0    # [m/s] a knock's speed, either way (a hard shove is ~5)


def _num(event: dict, key: str, default: float, bound: float) -> float:
    """event[key] (or `default`), a finite number within [-bound, bound]."""
    value = event.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or \
            not math.isfinite(value) or not -bound <= value <= bound:
        raise WorldError(f"{key}: expected a number in [{-bound:g}, {bound:g}], got {value!r}")
    return float(value)


def _standing(world: World, event: dict) -> Block:
    name = event.get("block")
    block = world.blocks.get(name) if isinstance(name, str) else None
    if block is None:
        raise WorldError(f"block: expected one of {sorted(world.blocks)}, got {name!r}")
    holder = world.holder(block.name)
    if holder is not None:
        raise WorldError(f"block {block.name} is held by {holder.agent}'s hand {holder.hand}")
    return block


def _add(world: World, event: dict) -> None:
    name, spec = event.get("block"), world.config.table
    if not isinstance(name, str) or not NAME.match(name) or name in RESERVED \
            or name == spec.name or name in world.blocks:
        raise WorldError(f"block: expected a new block name, got {name!r} "
                         f"(blocks: {sorted(world.blocks)}, table: {spec.name})")
    size = event.get("size", [2.0, 2.0])
    if not isinstance(size, list) or len(size) != 2 or \
            not all(isinstance(v, int | float) and 0.25 <= v <= 20 for v in size):
        raise WorldError(f"size: expected [width, height] in [0.25, 20] [m], got {size!r}")
    width, height = float(size[0]), float(size[1])
    offset, on = _num(event, "offset", 0.0, MAX_OFFSET), event.get("on", spec.name)
    if on == spec.name:
        x, bottom, ignore = _table_spot(world, event, width, height) + offset, spec.height, None
    else:
        ignore = _standing(world, {"block": on})
        if world.on_top_of(ignore):
            raise WorldError(f"on: {on} is not clear: {', '.join(world.on_top_of(ignore))} "
                             f"on it")
        x, bottom = ignore.box.x + offset, ignore.box.top
    box = Box(x, bottom + height / 2, 0.0, width, height)
    hit = world.obstacle(box, ignore=ignore)
    if hit is not None:
        raise WorldError(f"no room for {name} at x {x:g} m: it would hit {hit}")
    world.add_block(name, width, height).place(x, bottom)


def _table_spot(world: World, event: dict, width: float, height: float) -> float:
    spec = world.config.table
    if "column" in event:
        k = event["column"]
        if isinstance(k, bool) or not isinstance(k, int) or not 0 <= k < spec.columns:
            raise WorldError(f"column: expected an integer in [0, {spec.columns - 1}], got {k!r}")
        return spec.column_x(k)
    for k in range(spec.columns):
        box = Box(spec.column_x(k), spec.height + height / 2, 0.0, width, height)
        if world.obstacle(box) is None:
            return spec.column_x(k)
    raise WorldError(f"no free column on the table {spec.name}")


def _remove(world: World, event: dict) -> None:
    block = _standing(world, event)
    above = world.on_top_of(block)
    if above:
        raise WorldError(f"block {block.name} is not clear: {', '.join(above)} on it")
    world.remove_block(block)
    del world.blocks[block.name]


def _knock(world: World, event: dict) -> None:
    block = _standing(world, event)
    speed = _num(event, "speed", 3.0, MAX_KNOCK)
    block.body.velocity = (speed, 0.0)
    block.cause = ""


def _slip(world: World, event: dict) -> None:
    agent = event.get("agent")
    gripper = world.grippers.get(agent) if isinstance(agent, str) else None
    if gripper is None:
        raise WorldError(f"agent: expected one of {sorted(world.grippers)}, got {agent!r}")
    if gripper.holding is None:
        raise WorldError(f"{agent}'s hand {gripper.hand} holds nothing to drop")
    block = world.drop(gripper)
    gripper.count("blocks_dropped")
    world.note("dropped", agent=agent, block=block.name)


_DO = {"add": _add, "remove": _remove, "knock": _knock, "slip": _slip}
