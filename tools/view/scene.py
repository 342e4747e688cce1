"""What the web page needs to draw a world: the static map (sent once per world
configuration) and the moving parts of a snapshot (sent with every frame). Which keys are
static and what the map holds are the world's own hooks (Domain.static_keys and
Domain.scene, world/domain.py): the page (static/world.js) draws a world with a scene hook
itself on a canvas (driving and blocks); any other is shown as the domain's own PNG render,
made here on request, so a new world needs no edit here.
"""

from __future__ import annotations

import hashlib
import json
import tempfile
from pathlib import Path
from typing import Any


def _domain(snapshot: dict[str, Any]) -> Any:
    """The snapshot's Domain (world/domain.py), or None for a world not installed here."""
    from world.domain import domain_of
    from world.errors import ConfigError

    try:
        return domain_of(snapshot)
    except ConfigError:
        return None


def split(snapshot: dict[str, Any]) -> tuple[dict[str, Any], dict[str, Any]]:
    """(static part, moving part) of a snapshot dict: the static part is the keys its Domain
    names in ``static_keys`` (the same for a whole run; world/static.py)."""
    from world.static import split as split_static

    return split_static(snapshot)


def map_of(snapshot: dict[str, Any]) -> dict[str, Any]:
    """The static map of a snapshot's world, with an id that changes when the world does:
    "drawn" when its Domain has a ``scene`` hook (the page's own drawer of that domain draws
    it, with what the hook adds); otherwise the page shows the domain's PNG render."""
    from world.domain import DEFAULT_DOMAIN

    domain = str(snapshot.get("domain", DEFAULT_DOMAIN))
    spec = _domain(snapshot)
    static, _ = split(snapshot)
    ident = hashlib.sha256(json.dumps(static, sort_keys=True).encode()).hexdigest()[:12]
    drawn = spec is not None and spec.scene is not None
    body: dict[str, Any] = {"domain": domain, "id": ident, "drawn": drawn, **static}
    if drawn:
        body.update(spec.scene(snapshot))
    return body


def render_png(snapshots: list[dict[str, Any]], agent: str | None) -> bytes:
    """The domain's own picture of the last snapshot (with the path over all of them)."""
    from world.domain import domain_of

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "frame.png"
        domain_of(snapshots[-1]).render(snapshots, out, agent)
        return out.read_bytes()
