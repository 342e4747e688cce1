"""What the web page needs to draw a world, domain by domain: the static map (sent once per
world configuration) and the moving parts of a snapshot (sent with every frame). The page
(static/view.js) draws driving and blocks itself on a canvas; any other domain is shown as
the domain's own PNG render (world/domain.py), made here on request.
"""

from __future__ import annotations

import hashlib
import json
import tempfile
from pathlib import Path
from typing import Any

STATIC_KEYS = {"driving": ("config",), "blocks": ("table", "resolution"), "office": ("config",)}
"""Snapshot keys that stay the same for a whole run: sent in the map, not in every frame."""

DRAWN = frozenset({"driving", "blocks"})
"""Domains the page draws from snapshot dicts; others get a PNG from the domain's renderer."""


def split(snapshot: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """(static part, moving part) of a snapshot dict."""
    keys = STATIC_KEYS.get(str(snapshot.get("domain", "driving")), ())
    return ({k: snapshot[k] for k in keys if k in snapshot},
            {k: v for k, v in snapshot.items() if k not in keys})


def map_of(snapshot: dict[str, Any]) -> dict[str, Any]:
    """The static map of a snapshot's world, with an id that changes when the world does."""
    domain = str(snapshot.get("domain", "driving"))
    static, _ = split(snapshot)
    ident = hashlib.sha256(json.dumps(static, sort_keys=True).encode()).hexdigest()[:12]
    body: dict[str, Any] = {"domain": domain, "id": ident, "drawn": domain in DRAWN,
                            **static}
    if domain == "driving":
        body.update(_city(snapshot["config"]))
    return body


def _city(config: dict[str, Any]) -> dict[str, Any]:
    """Streets, intersections and buildings of the driving city [m], plus its road widths."""
    from world.driving import city
    from world.driving.config import load_world_config

    c = city.build_city(load_world_config(config))
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


def render_png(snapshots: list[dict[str, Any]], agent: str | None) -> bytes:
    """The domain's own picture of the last snapshot (with the path over all of them)."""
    from world.domain import domain_of

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "frame.png"
        domain_of(snapshots[-1]).render(snapshots, out, agent)
        return out.read_bytes()
