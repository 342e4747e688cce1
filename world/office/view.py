"""What the tools draw of the office world beyond its own render: `teleo plot`'s panel (how
far each robot has travelled). The view shows the world's own PNG render (no scene hook), so
tools/ names no world (world/domain.py).
"""

from __future__ import annotations

from collections import defaultdict
from typing import Any

from world.domain import RunSeries

PLOT_TITLE = "distance each robot has travelled"


def plot_panel(ax: Any, s: RunSeries) -> bool:
    """Each robot's travelled distance [m] (its travel_cm counter) over world time [s]."""
    travel: dict[str, list[tuple[int, float]]] = defaultdict(list)
    for c in s.cycles:
        for agent, counts in s.snapshots[c].get("counters", {}).items():
            if "travel_cm" in counts:
                travel[agent].append((c, counts["travel_cm"] / 100.0))
    for agent, rows in sorted(travel.items()):
        ax.plot(s.t([c for c, _ in rows]), [m for _, m in rows], label=f"{agent} travelled")
    ax.set_ylabel("distance [m]")
    return bool(travel)
