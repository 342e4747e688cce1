"""Seed 000's Blocks World actions (Figure 3), each done in one cycle or refused with a reason.

    (*pickup B T)     lift B off the table T: B stands on T, nothing on it, the hand is empty
    (*unstack B A)    lift B off block A: B stands on A, nothing on B, the hand is empty
    (*putdown B T)    set the held B down on T, in its leftmost free column
    (*stack B A)      set the held B down centred on A: A stands, flat, with nothing on it,
                      and B fits there without touching another block
    (*wait)           nothing: the gripper stays and keeps what it holds (a silent agent's
                      safe action)

One gripper does one action a cycle: a second is refused. A refusal changes nothing and
names the agent, the action and what is wrong: "ME: (*unstack B A): B is not clear: C is on it".
"""

from __future__ import annotations

from typing import Any, Protocol

from world.blocks.block import Block, Box
from world.blocks.config import BlocksConfig
from world.blocks.gripper import Gripper
from world.errors import WorldError

FORMS = {"*pickup": ("?block", "?table"), "*unstack": ("?block", "?from"),
         "*putdown": ("?block", "?table"), "*stack": ("?block", "?to"), "*wait": ()}


class Refused(WorldError):
    """An action the world does not carry out; the message is the reason."""


class World(Protocol):
    """The part of simulation.BlocksWorld that actions use."""

    config: BlocksConfig
    blocks: dict[str, Block]

    def holder(self, name: str) -> Gripper | None: ...
    def supports(self, block: Block) -> list[str]: ...
    def on_top_of(self, block: Block) -> list[str]: ...
    def obstacle(self, box: Box, ignore: Block | None = None) -> str | None: ...
    def set_down(self, gripper: Gripper, x: float, bottom: float) -> Block: ...
    def lift(self, gripper: Gripper, block: Block) -> None: ...


def text(action: Any) -> str:
    """An action as the program writes it: ``(*stack C A)``."""
    if isinstance(action, list | tuple):
        return "(" + " ".join(str(a) for a in action) + ")"
    return repr(action)


def apply_action(world: World, gripper: Gripper, action: Any) -> dict[str, Any]:
    """Do one action for the gripper's agent; its outcome {"action", "status", "reason"}."""
    shown = list(action) if isinstance(action, list | tuple) else [repr(action)]
    try:
        name, args = _form(action)
        if name == "*wait":
            return {"action": shown, "status": "done", "reason": ""}
        if gripper.acted is not None:
            raise Refused(f"the gripper {gripper.hand} already acted this cycle: "
                          f"{text(gripper.acted)}")
        gripper.acted = shown
        _DO[name](world, gripper, *args)
    except Refused as exc:
        gripper.count("actions_failed")
        return {"action": shown, "status": "failed",
                "reason": f"{gripper.agent}: {text(action)}: {exc}"}
    gripper.count("actions_done")
    return {"action": shown, "status": "done", "reason": ""}


def _form(action: Any) -> tuple[str, list[str]]:
    if not isinstance(action, list | tuple) or not action or not isinstance(action[0], str):
        raise Refused("expected [name, arg, ...] such as ['*stack', 'C', 'A']")
    name, *args = action
    if name not in FORMS:
        raise Refused(f"unknown action {name}; the Blocks World knows {', '.join(FORMS)}")
    form = FORMS[name]
    if len(args) != len(form):
        raise Refused(f"expected {len(form)} arguments ({' '.join([name, *form])}), "
                      f"got {len(args)}")
    for k, a in enumerate(args):
        if not isinstance(a, str):
            raise Refused(f"argument {k + 1} {form[k]}: expected a name, got {a!r}")
    return name, args


def _block(world: World, name: str) -> Block:
    block = world.blocks.get(name)
    if block is None:
        what = "the table, not a block" if name == world.config.table.name else "an unknown block"
        raise Refused(f"{name} is {what}; blocks: {', '.join(sorted(world.blocks))}")
    return block


def _table(world: World, name: str) -> None:
    table = world.config.table.name
    if name != table:
        what = "a block, not the table" if name in world.blocks else "unknown"
        raise Refused(f"{name} is {what}; the table is {table}")


def _liftable(world: World, gripper: Gripper, block: Block, source: str) -> None:
    if gripper.holding is not None:
        raise Refused(f"the hand {gripper.hand} is not empty: it holds {gripper.holding.name}")
    other = world.holder(block.name)
    if other is not None:
        raise Refused(f"{block.name} is held by {other.agent}'s hand {other.hand}")
    under = world.supports(block)
    if source not in under:
        where = " and ".join(under) if under else "nothing (it is falling)"
        raise Refused(f"{block.name} is not on {source}: it is on {where}")
    above = world.on_top_of(block)
    if above:
        raise Refused(f"{block.name} is not clear: {', '.join(above)} on it")


def _held(gripper: Gripper, name: str) -> Block:
    block = gripper.holding
    if block is None or block.name != name:
        now = block.name if block else "nothing"
        raise Refused(f"the hand {gripper.hand} is not holding {name}: it holds {now}")
    return block


def pickup(world: World, gripper: Gripper, name: str, table: str) -> None:
    block = _block(world, name)
    _table(world, table)
    _liftable(world, gripper, block, table)
    world.lift(gripper, block)


def unstack(world: World, gripper: Gripper, name: str, source: str) -> None:
    block = _block(world, name)
    _block(world, source)
    _liftable(world, gripper, block, source)
    world.lift(gripper, block)


def putdown(world: World, gripper: Gripper, name: str, table: str) -> None:
    block = _held(gripper, name)
    _table(world, table)
    spec = world.config.table
    lo, hi = spec.span
    for k in range(spec.columns):
        x = spec.column_x(k)
        box = Box(x, spec.height + block.height / 2, 0.0, block.width, block.height)
        if box.left >= lo and box.right <= hi and world.obstacle(box) is None:
            world.set_down(gripper, x, spec.height)
            gripper.count("blocks_moved")
            return
    raise Refused(f"no free place for {name} (width {block.width:g} m) on the table {table}: "
                  f"its {spec.columns} columns are taken")


def stack(world: World, gripper: Gripper, name: str, target: str) -> None:
    block = _held(gripper, name)
    if target == name:
        raise Refused(f"{name} cannot be stacked on itself")
    under = _block(world, target)
    other = world.holder(target)
    if other is not None:
        raise Refused(f"{target} is held by {other.agent}'s hand {other.hand}")
    above = world.on_top_of(under)
    if above:
        raise Refused(f"{target} is not clear: {', '.join(above)} on it")
    if not under.upright or under.moving:
        raise Refused(f"{target} does not stand still and flat: nothing can go on it")
    base = under.box
    box = Box(base.x, base.top + block.height / 2, 0.0, block.width, block.height)
    hit = world.obstacle(box, ignore=under)
    if hit is not None:
        raise Refused(f"no room for {name} (width {block.width:g} m) on {target}: "
                      f"it would hit {hit}")
    world.set_down(gripper, base.x, base.top)
    gripper.count("blocks_moved")


_DO = {"*pickup": pickup, "*unstack": unstack, "*putdown": putdown, "*stack": stack}
