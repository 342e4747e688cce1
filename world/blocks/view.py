"""What the tools draw of the Blocks World beyond its own render: the view's static map (none
beyond the table and resolution the snapshot carries: the page's blocks drawer,
tools/view/static/world.js, draws the rest from each frame) and `teleo plot`'s panel (each
block's height). Both are hooks of the Domain (world/domain.py), so tools/ names no world.
"""

from __future__ import annotations

from collections import defaultdict
from typing import Any

from world.domain import RunSeries

PLOT_TITLE = "block heights"


def scene(snapshot: dict[str, Any]) -> dict[str, Any]:
    """Nothing beyond the static keys: the page draws the table and blocks from them."""
    return {}


def plot_panel(ax: Any, s: RunSeries) -> bool:
    """Each block's height [m] over world time [s]."""
    heights: dict[str, list[tuple[int, float]]] = defaultdict(list)
    for c in s.cycles:
        for b in s.snapshots[c].get("blocks", ()):
            heights[b["name"]].append((c, float(b["y"])))
    for name, rows in sorted(heights.items()):
        ax.plot(s.t([c for c, _ in rows]), [y for _, y in rows], label=f"block {name}")
    ax.set_ylabel("height [m]")
    return bool(heights)
