"""The Blocks World (seed 000, Figure 3) on a pymunk space: a static table, dynamic blocks that
stand under gravity on it and on each other, and one gripper per agent.

An action takes one cycle: the gripper lifts a block out of the physics or sets one down, flat
and still, on the table or centred on another block (actions.py); then `step` lets gravity and
contacts settle the world for dt [s] in fixed substeps. pymunk is deterministic for a fixed step
and insertion order, so one config and seed give the same run, step for step. A block that
comes to rest somewhere other than where it was put has fallen (an unstable start, an event);
the fall is reported in the next snapshot's events, and counted against the agent whose put
started it.
"""

from __future__ import annotations

from typing import Any

import pymunk

from world.base import BaseWorld, deg
from world.blocks.actions import apply_action
from world.blocks.block import Block, Box
from world.blocks.config import BlocksConfig
from world.blocks.events import apply_event
from world.blocks.gripper import Gripper
from world.blocks.snapshot import BlocksSnapshot, BlockState, HandState
from world.blocks.table import build_table
from world.errors import WorldError

SUBSTEP = 1 / 120       # [s] the physics step
GRAVITY = -9.81         # [m/s^2]
TOUCH = 0.05            # [m] a lower edge this close to a top face rests on it
OVERLAP = 0.05          # [m] of horizontal overlap needed to rest on something
FELL_DROP = 0.25        # a block that came to rest lower by this part of its height fell
FELL_SHIFT = 0.25       # [m] ... or this far sideways
FLOOR = "floor"


class BlocksWorld(BaseWorld):
    """One table, its blocks and a gripper per agent id (hands H1, H2, ... in agent order)."""

    def __init__(self, config: BlocksConfig, seed: int, agents: list[str]) -> None:
        if not agents or len(set(agents)) != len(agents):
            raise WorldError(f"BlocksWorld: expected distinct agent ids, got {agents}")
        unknown = sorted(set(config.holding) - set(agents))
        if unknown:
            raise WorldError(f"BlocksWorld: [world] holding names {unknown}, not agents of "
                             f"this run (agents: {agents})")
        self.config, self.seed, self.cycle = config, seed, 0
        self.space = pymunk.Space()
        self.space.gravity = (0.0, GRAVITY)
        self.space.iterations = 30
        self.space.collision_slop = 0.002
        build_table(self.space, config.table)
        self.blocks: dict[str, Block] = {}
        self.grippers = {a: Gripper(a, f"H{k + 1}", config.table.column_x(k))
                         for k, a in enumerate(agents)}
        self._events: list[dict[str, Any]] = []      # reported in the current snapshot
        self._incoming: list[dict[str, Any]] = []    # happening during the coming step
        self._placed_by: dict[str, str] = {}         # block -> agent that loaded it this cycle
        for k, tower in enumerate(config.towers):
            x, bottom = config.table.column_x(k), config.table.height
            for name in tower:
                block = self.add_block(name, *_size(config, name))
                x += config.offsets.get(name, 0.0)
                block.place(x, bottom)
                bottom += block.height
        for agent, name in sorted(config.holding.items()):
            self.grippers[agent].holding = Block(name, *_size(config, name))
            self.blocks[name] = self.grippers[agent].holding

    # -- what actions and events use ----------------------------------------------------------
    def add_block(self, name: str, width: float, height: float) -> Block:
        """A new block in the space (placed by the caller)."""
        block = Block(name, width, height)
        self.blocks[name] = block
        self.space.add(block.body, block.shape)
        return block

    def remove_block(self, block: Block) -> None:
        """Take a block out of the space (picked up, or taken away by an event)."""
        self.space.remove(block.body, block.shape)

    def standing(self) -> list[Block]:
        """The blocks in the physics (not held), by name."""
        return [b for n, b in sorted(self.blocks.items()) if self.holder(n) is None]

    def holder(self, name: str) -> Gripper | None:
        """The gripper that holds block `name`, if any."""
        return next((g for g in self.grippers.values()
                     if g.holding is not None and g.holding.name == name), None)

    def supports(self, block: Block) -> list[str]:
        """What the block rests on: the table's name, "floor", or blocks' names, sorted."""
        box, out = block.box, []
        lo, hi = self.config.table.span
        if abs(box.bottom - self.config.table.height) < TOUCH and \
                min(box.right, hi) - max(box.left, lo) > OVERLAP:
            out.append(self.config.table.name)
        if abs(box.bottom) < TOUCH:
            out.append(FLOOR)
        for other in self.standing():
            o = other.box
            if other is not block and abs(box.bottom - o.top) < TOUCH and \
                    min(box.right, o.right) - max(box.left, o.left) > OVERLAP:
                out.append(other.name)
        return sorted(out)

    def beneath(self, block: Block) -> list[str]:
        """Every block the block rests on, directly or through others."""
        out: list[str] = []
        todo = [n for n in self.supports(block) if n in self.blocks]
        while todo:
            name = todo.pop()
            if name not in out:
                out.append(name)
                todo += [n for n in self.supports(self.blocks[name]) if n in self.blocks]
        return sorted(out)

    def on_top_of(self, block: Block) -> list[str]:
        """The blocks resting on this one."""
        return [b.name for b in self.standing() if block.name in self.supports(b)]

    def obstacle(self, box: Box, ignore: Block | None = None) -> str | None:
        """The first standing block a box at this place would overlap, if any."""
        for other in self.standing():
            if other is not ignore and box.overlaps(other.box, gap=TOUCH):
                return other.name
        return None

    def highest(self) -> float:
        """The top [m] of the highest standing block (the table's top if none)."""
        return max([self.config.table.height, *(b.box.top for b in self.standing())])

    def set_down(self, gripper: Gripper, x: float, bottom: float) -> Block:
        """The gripper lets go of its block at rest there; it rejoins the physics."""
        block = gripper.holding
        if block is None:
            raise WorldError(f"{gripper.agent}: set_down: the hand {gripper.hand} holds nothing")
        gripper.holding, gripper.x = None, x
        block.place(x, bottom)
        self.space.add(block.body, block.shape)
        for name in [block.name, *self.beneath(block)]:
            self._placed_by.setdefault(name, gripper.agent)
        return block

    def drop(self, gripper: Gripper) -> Block:
        """The gripper loses its block where it holds it: it falls (a fault, events.py)."""
        held = gripper.holding
        bottom = gripper.y(self.highest()) - (held.height if held else 0.0)
        block = self.set_down(gripper, gripper.x, bottom)
        self._placed_by = {b: a for b, a in self._placed_by.items() if a != gripper.agent}
        block.rest = None        # it lands wherever it lands, counted as dropped already
        return block

    def lift(self, gripper: Gripper, block: Block) -> None:
        """The gripper takes a standing block out of the physics."""
        gripper.x = block.box.x
        self.remove_block(block)
        gripper.holding, block.rest = block, None

    def note(self, kind: str, **fields: Any) -> None:
        """An event of the coming step, reported in the next snapshot."""
        self._incoming.append({"kind": kind, "cycle": self.cycle, **fields})

    # -- the contract (world/domain.py) ------------------------------------------------------
    def actors(self) -> dict[str, Gripper]:
        """Each agent's gripper (world/base.py: the guards of apply_actions)."""
        return self.grippers

    def act(self, actor: Gripper, actions: Any) -> list[dict[str, Any]]:
        """Apply an agent's actions of this cycle in order; one outcome each, never raises."""
        return [apply_action(self, actor, a) for a in actions]

    def safe_actions(self, agent: str) -> list[list[Any]]:
        """A silent agent's gripper stops: it stays where it is and keeps what it holds."""
        return [["*wait"]]

    def apply_event(self, event: dict[str, Any]) -> dict[str, Any]:
        """Apply a scenario event (events.py); {"event", "status", "reason"}, never raises."""
        return apply_event(self, event)

    def step(self) -> None:
        """Let the physics settle for dt [s] in fixed substeps; then tell falls from puts."""
        for _ in range(round(self.config.dt / SUBSTEP)):
            self.space.step(SUBSTEP)
        for block in self.standing():
            self._watch(block, self._placed_by.get(block.name, ""))
        for g in self.grippers.values():
            g.acted = None
        self._placed_by = {}
        self.cycle += 1
        self._events, self._incoming = self._incoming, []

    def _watch(self, block: Block, placer: str) -> None:
        """Blame a block that starts to move on the agent that set it, or a block on it, down
        this cycle; when it rests again lower or elsewhere than before, it fell."""
        if block.moving:
            if not block.unsettled:
                block.unsettled, block.cause = True, block.cause or placer
            return
        block.unsettled = False
        now = block.box
        was, block.rest = block.rest, now
        agent, block.cause = block.cause, ""
        if was is None or (was.bottom - now.bottom <= FELL_DROP * block.height
                           and abs(was.x - now.x) <= FELL_SHIFT):
            return       # resting where it was, or landing after a drop (counted then)
        if agent in self.grippers:
            self.grippers[agent].count("blocks_dropped")
        self._incoming.append({"kind": "fell", "cycle": self.cycle, "block": block.name,
                               "agent": agent, "x": round(now.x, 3), "y": round(now.bottom, 3),
                               "on": self.supports(block)})

    def snapshot(self) -> BlocksSnapshot:
        """The frozen observable state of the current cycle."""
        top = self.highest()
        hands = {g.agent: HandState(g.agent, g.hand, g.x, g.y(top),
                                    g.holding.name if g.holding else "")
                 for g in self.grippers.values()}
        blocks = []
        for name, b in sorted(self.blocks.items()):
            g = self.holder(name)
            if g is None:
                box = b.box
                blocks.append(BlockState(name, box.x, box.y, deg(box.angle), b.width, b.height))
            else:
                y = hands[g.agent].y - b.height / 2
                blocks.append(BlockState(name, g.x, y, 0.0, b.width, b.height, g.agent))
        return BlocksSnapshot(self.cycle, round(self.cycle * self.config.dt, 9), self.config.table,
                              self.config.resolution, tuple(blocks), tuple(hands.values()),
                              {a: dict(g.counters) for a, g in self.grippers.items()},
                              tuple(self._events))


def _size(config: BlocksConfig, name: str) -> tuple[float, float]:
    spec = config.block(name)
    return spec.width, spec.height

