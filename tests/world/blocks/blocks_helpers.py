"""Helpers for the Blocks World tests: worlds built from a table of towers, one action or
event at a time, and the towers of a support map (block -> what it stands on) laid out as
tests/lang/test_blocks.py's hand-made model lays them out."""

from __future__ import annotations

from typing import Any

from world.blocks import create, perceive
from world.blocks.simulation import BlocksWorld


def world(towers: list[list[str]] | None = None, agents: tuple[str, ...] = ("ME",),
          seed: int = 0, **table: Any) -> BlocksWorld:
    """A BlocksWorld of these towers (bottom first) and other `[world]` keys."""
    if towers is not None:
        table["towers"] = towers
    return create(table, seed, list(agents))


def act(w: BlocksWorld, *action: Any, agent: str = "ME") -> dict[str, Any]:
    """Apply one action, step the physics, return its outcome."""
    [outcome] = w.apply_actions(agent, [list(action)])
    w.step()
    return outcome


def settle(w: BlocksWorld, cycles: int) -> None:
    for _ in range(cycles):
        w.apply_actions("ME", w.safe_actions("ME"))
        w.step()


def seen(w: BlocksWorld, agent: str = "ME") -> list[list[Any]]:
    """What the agent perceives now."""
    return perceive(w.snapshot_dict(), agent)


def blocks_seen(w: BlocksWorld) -> dict[str, tuple]:
    """block -> (xpos, ypos, height) as perceived."""
    return {p[1]: (p[3], p[5], p[7]) for p in seen(w) if p[0] == "block"}


def towers_of(support: dict[str, str]) -> list[list[str]]:
    """The towers (bottom first) of a support map, in the columns the hand-made model gives
    them: going through the blocks by name, each new bottom block takes the next column. A
    block supported by "hand" is held and stands in no tower."""
    def bottom(b: str) -> str:
        return b if support[b] == "T" else bottom(support[b])

    order: list[str] = []
    for b in sorted(support):
        if support[b] != "hand" and bottom(b) not in order:
            order.append(bottom(b))
    above = {under: b for b, under in support.items()}
    towers = []
    for base in order:
        tower = [base]
        while tower[-1] in above:
            tower.append(above[tower[-1]])
        towers.append(tower)
    return towers
