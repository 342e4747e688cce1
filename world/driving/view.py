"""What the tools draw of the driving world beyond its own render: the view's static map
(streets, intersections, buildings [m], drawn by the page's driving drawer,
tools/view/static/world.js) and `teleo plot`'s panel (each agent's speed and the limit it
perceives). Both are hooks of the Domain (world/domain.py), so tools/ names no world.
"""

from __future__ import annotations

from typing import Any

from world.domain import RunSeries

PLOT_TITLE = "speed and the perceived limit"


def scene(snapshot: dict[str, Any]) -> dict[str, Any]:
    """Streets, intersections and buildings of the driving city [m], plus its road widths."""
    from world.driving import city
    from world.driving.config import load_world_config

    c = city.build_city(load_world_config(snapshot["config"]))
    return {
        "size": list(c.size),
        "road_half": city.ROAD_HALF, "lane_width": city.LANE_WIDTH,
        "sidewalk": city.SIDEWALK_OUTER,
        "segments": [{"id": s.id, "street": s.street, "a": [s.x0, s.y0],
                      "b": list(s.point(s.length, 0.0))} for s in c.segments],
        "intersections": [{"id": n.id, "x": n.x, "y": n.y} for n in c.intersections],
        "buildings": [{"street": b.street, "address": b.address, "corners": b.corners,
                       "curb": b.curb} for b in c.buildings],
    }


def plot_panel(ax: Any, s: RunSeries) -> bool:
    """Each agent's speed [m/s] and the limit it perceives, over world time [s]."""
    for agent in s.agents:
        rows = sorted(s.percepts[agent].items())
        speed = [(c, r["self"]["speed"]) for c, r in rows if "speed" in r.get("self", {})]
        limit = [(c, r["self"]["limit"]) for c, r in rows if "limit" in r.get("self", {})]
        if speed:
            ax.plot(s.t([c for c, _ in speed]), [v for _, v in speed], label=f"{agent} speed")
        if limit:
            ax.step(s.t([c for c, _ in limit]), [v for _, v in limit], where="post",
                    linestyle="--", label=f"{agent} limit")
    ax.set_ylabel("speed [m/s]")
    return bool(s.agents)
