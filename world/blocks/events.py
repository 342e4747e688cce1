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
Every field is checked against EVENTS before use (type, range, no unknown field); at most
MAX_BLOCKS blocks.
"""

from __future__ import annotations

from typing import Any, Protocol

from bus.schema import FieldError, Int, Num, Record, Str, Tagged, TupleOf
from world.blocks.block import Block, Box
from world.blocks.config import NAME, RESERVED, BlocksConfig
from world.blocks.gripper import Gripper
from world.domain import event_outcome
from world.errors import WorldError

MAX_OFFSET = 20.0   # [m] an added block's offset from its support's centre
MAX_KNOCK = 30.0    # [m/s] a knock's speed, either way (a hard shove is ~5)
MAX_BLOCKS = 200    # blocks on the table at most (an added one beyond is refused)

_BLOCK = Str(what="a block name")
_SIDE = Num(0.25, 20.0)
EVENTS = Tagged({
    "add": Record({"block": _BLOCK}, {"on": Str(what="the table or a block name"),
                                      "size": TupleOf(_SIDE, _SIDE, what="[width, height] [m]"),
                                      "offset": Num(-MAX_OFFSET, MAX_OFFSET),
                                      "column": Int(0, 10**6, what="a column")}),
    "remove": Record({"block": _BLOCK}),
    "knock": Record({"block": _BLOCK}, {"speed": Num(-MAX_KNOCK, MAX_KNOCK)}),
    "slip": Record({"agent": Str(what="an agent's name")}),
})
"""The Blocks World's events and their fields (the module's docstring): checked before use."""
KINDS = EVENTS.kinds


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
        _DO[EVENTS.check(event)["kind"]](world, event)
    except (WorldError, FieldError) as exc:
        return event_outcome(event, f"inject: {exc}")
    return event_outcome(event)


def _standing(world: World, event: dict) -> Block:
    name = event["block"]
    block = world.blocks.get(name)
    if block is None:
        raise WorldError(f"block: expected one of {sorted(world.blocks)}, got {name!r}")
    holder = world.holder(block.name)
    if holder is not None:
        raise WorldError(f"block {block.name} is held by {holder.agent}'s hand {holder.hand}")
    return block


def _add(world: World, event: dict) -> None:
    name, spec = event["block"], world.config.table
    if not NAME.match(name) or name in RESERVED or name == spec.name or name in world.blocks:
        raise WorldError(f"block: expected a new block name, got {name!r} "
                         f"(blocks: {sorted(world.blocks)}, table: {spec.name})")
    if len(world.blocks) >= MAX_BLOCKS:
        raise WorldError(f"block: the table has {len(world.blocks)} blocks, the most it takes")
    size = event.get("size", [2.0, 2.0])
    width, height = float(size[0]), float(size[1])
    offset, on = float(event.get("offset", 0.0)), event.get("on", spec.name)
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
        raise WorldError(f"block: no room for {name} at x {x:g} m: it would hit {hit}")
    world.add_block(name, width, height).place(x, bottom)


def _table_spot(world: World, event: dict, width: float, height: float) -> float:
    spec = world.config.table
    if "column" in event:
        k = event["column"]
        if not k < spec.columns:
            raise WorldError(f"column: expected an integer in [0, {spec.columns - 1}], got {k!r}")
        return spec.column_x(k)
    for k in range(spec.columns):
        box = Box(spec.column_x(k), spec.height + height / 2, 0.0, width, height)
        if world.obstacle(box) is None:
            return spec.column_x(k)
    raise WorldError(f"block: no free column on the table {spec.name} for {event['block']}")


def _remove(world: World, event: dict) -> None:
    block = _standing(world, event)
    above = world.on_top_of(block)
    if above:
        raise WorldError(f"block {block.name} is not clear: {', '.join(above)} on it")
    world.remove_block(block)
    del world.blocks[block.name]


def _knock(world: World, event: dict) -> None:
    block = _standing(world, event)
    speed = float(event.get("speed", 3.0))
    block.body.velocity = (speed, 0.0)
    block.cause = ""


def _slip(world: World, event: dict) -> None:
    agent = event["agent"]
    gripper = world.grippers.get(agent)
    if gripper is None:
        raise WorldError(f"agent: expected one of {sorted(world.grippers)}, got {agent!r}")
    if gripper.holding is None:
        raise WorldError(f"{agent}'s hand {gripper.hand} holds nothing to drop")
    block = world.drop(gripper)
    gripper.count("blocks_dropped")
    world.note("dropped", agent=agent, block=block.name)


_DO = {"add": _add, "remove": _remove, "knock": _knock, "slip": _slip}
